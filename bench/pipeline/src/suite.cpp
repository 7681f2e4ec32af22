#include "hoilcd/bench/pipeline/suite.h"

#include <filesystem>

#include "hoilcd/bench/pipeline/suite_report.h"
#include "hoilcd/bench/report/output_folder.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/file_io.h"
#include "hoilcd/core/util/folder_lock.h"
#include "hoilcd/core/util/safe_text.h"
#include "hoilcd/sim/generate/generator.h"
#include "hoilcd/sim/output/sequence.h"
#include "hoilcd/sim/scene/scene.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

// The checksum of a scene file's bytes; null when it cannot be read (its runs will fail, naming it).
nlohmann::json SceneChecksum(const std::string& path) {
  try {
    return ChecksumOfFile(path);
  } catch (const InputError&) {
    return nullptr;
  }
}

// The run's scene: a generated sequence's file is written first (only when its bytes change).
Scene LoadRunScene(const SuiteSequence& seq, int seed, const std::string& out_dir) {
  std::string path = seq.scene_path;
  if (seq.generated) {
    path = out_dir + "/scenes/" + seq.name + ".json";
    const std::string text =
        SceneFileText(GenerateScene(seq.layout, seq.generator_seed, seq.generator_index, GeneratorOptions()));
    std::error_code ec;
    bool same = false;
    if (fs::exists(path, ec)) {
      try {
        same = ReadFileBytes(path) == text;
      } catch (const InputError&) {
        same = false;
      }
    }
    if (!same) WriteFileAtomic(path, text);
  }
  std::vector<std::string> overrides = seq.sets;
  overrides.push_back("seed=" + std::to_string(seed));
  return LoadScene(path, overrides);
}

}  // namespace

SuiteOptions::SuiteOptions() { Table().FillDefaults(this); }

const OptionTable<SuiteOptions>& SuiteOptions::Table() {
  using O = SuiteOptions;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("output_dir", &O::output_dir, "", {}, "suite.json, scenes/ and runs/ go here")
          .Rule("output_dir", [](const O& o) { return o.output_dir.empty() ? "the output folder must be given" : ""; })
          .Add("split", &O::split, "all", {"dev", "test", "all"}, "which sequences run: dev, test or all")
          .Rule("shard", [](const O& o) { return o.shard.Check(); })
          .Nest("run", &O::run, RunOptions::Table());
  return table;
}

std::string SuiteOptions::Check() const { return Table().FirstProblem(*this); }

nlohmann::json SuiteIdentity(const Suite& suite, const std::string& split, const nlohmann::json& bench) {
  nlohmann::json sequences = nlohmann::json::array();
  for (const SuiteSequence& seq : suite.sequences) {
    if (split != "all" && seq.split != split) continue;
    nlohmann::json s = {{"name", seq.name}};
    if (seq.generated) {
      // The generator's version too: another version makes another scene from the same spec.
      s["generate"] = {{"layout", seq.layout},
                       {"seed", seq.generator_seed},
                       {"index", seq.generator_index},
                       {"generator_version", kGeneratorVersion}};
    } else {
      s["scene_checksum"] = SceneChecksum(seq.scene_path);
    }
    s["seeds"] = seq.seeds;
    s["set"] = seq.sets;
    s["split"] = seq.split;
    sequences.push_back(s);
  }
  nlohmann::json runs = nlohmann::json::array();
  for (const SuiteRunSpec& run : SuiteRuns(suite, split)) runs.push_back(run.name);
  return {{"name", suite.name},     {"description", suite.description},
          {"sequences", sequences}, {"split", split},
          {"bench", bench},         {"runs", runs}};
}

std::vector<SuiteRunResult> RunSuite(const Suite& suite, const BenchOptions& bench, const SuiteOptions& options,
                                     const SuiteRunCallback& before_run) {
  if (const std::string problem = options.Check(); !problem.empty()) throw InputError("suite", problem);
  const std::string& out = options.output_dir;
  // "suite" and "runs": the keys of every suite.json, this one's and an older hoilcd's.
  CheckOutputFolder(out, {"suite.json", {"suite", "runs"}, "suite"});
  // One suite at a time in a folder: a second is refused by name. Suites sharing a --cache share
  // its datasets through their own locks (RunScene).
  const FolderLock lock(out, FolderLock::IfBusy::kRefuse);
  CreateOutputFolder(out + "/runs");
  CreateOutputFolder(out + "/scenes");
  const nlohmann::json bench_json = BenchSettingsJson(bench);
  const nlohmann::json identity = SuiteIdentity(suite, options.split, bench_json);
  const std::vector<SuiteRunSpec> runs = ShardOf(SuiteRuns(suite, options.split), options.shard);
  nlohmann::json marker = {{"suite", {{"name", suite.name}, {"file", SafeText(suite.path)}}},
                           {"identity", identity},
                           {"identity_hash", ChecksumOf(identity.dump())},
                           {"shard", {{"index", options.shard.index}, {"count", options.shard.count}}},
                           {"runs", nlohmann::json::array()},
                           {"failed", nlohmann::json::array()},
                           {"finished", false}};
  for (const SuiteRunSpec& run : runs) marker["runs"].push_back(run.name);
  const auto write_marker = [&] {
    WriteFileAtomic(out + "/suite.json", marker.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  };
  write_marker();

  const std::vector<std::string> methods = bench_json.at("methods").get<std::vector<std::string>>();
  std::vector<SuiteRunResult> results;
  for (size_t i = 0; i < runs.size(); ++i) {
    const SuiteRunSpec& run = runs[i];
    const SuiteSequence& seq = suite.sequences[run.sequence];
    const std::string dir = out + "/runs/" + run.name;
    SuiteRunResult result;
    try {
      const Scene scene = LoadRunScene(seq, run.seed, out);
      const RecordedRun recorded{
          dir,
          "suite_run.json",
          {{"sequence", seq.name}, {"seed", run.seed}, {"scene_hash", scene.hash}, {"bench", bench_json}}};
      const bool kept = recorded.Kept();
      if (before_run) before_run(static_cast<int>(i) + 1, static_cast<int>(runs.size()), run, kept);
      if (!kept) recorded.Run(scene, bench, options.run);
      result = ReadSuiteRunResult(run.name, dir + "/report.json", methods);
    } catch (const RenderInterrupted&) {
      throw;  // Ctrl-C stops the suite; a rerun resumes it
    } catch (const std::exception& e) {
      if (options.run.cancel != nullptr && options.run.cancel->load()) throw;  // stopped, not failed
      result = SuiteRunResult{run.name, e.what(), {}, {}, seq.name};
      if (result.error.empty()) result.error = "failed without a message";
      marker["failed"].push_back({{"run", run.name}, {"error", result.error}});
      write_marker();
    }
    results.push_back(result);
  }
  marker["finished"] = true;
  write_marker();
  return results;
}

}  // namespace hoilcd
