#include "hoilcd/bench/pipeline/suite.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "hoilcd/bench/evaluation/safe_text.h"
#include "hoilcd/bench/report/output_folder.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/file_io.h"
#include "hoilcd/sim/generate/generator.h"
#include "hoilcd/sim/output/sequence.h"
#include "hoilcd/sim/scene/scene.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

double Metric(const nlohmann::json& method, const char* key) {
  const auto it = method.find(key);
  return it != method.end() && it->is_number() ? it->get<double>() : NAN;
}

// The run's scene: a generated sequence's file is written first (only when its bytes change).
Scene LoadRunScene(const SuiteSequence& seq, int seed, const std::string& out_dir) {
  std::string path = seq.scene_path;
  if (seq.generated) {
    path = out_dir + "/scenes/" + seq.name + ".json";
    const std::string text = SceneFileText(GenerateScene(seq.layout, seq.generator_seed, seq.generator_index, GeneratorOptions()));
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
          .Add("output_dir", &O::output_dir, "", {}, "suite.json, scenes/, runs/ and suite_report.{json,md} go here")
          .Rule("output_dir", [](const O& o) { return o.output_dir.empty() ? "the output folder must be given" : ""; })
          .Add("split", &O::split, "all", {"dev", "test", "all"}, "which sequences run: dev, test or all")
          .Nest("run", &O::run, RunOptions::Table());
  return table;
}

std::string SuiteOptions::Check() const { return Table().FirstProblem(*this); }

SuiteSummary RunSuite(const Suite& suite, const BenchOptions& bench, const SuiteOptions& options,
                      const SuiteRunCallback& before_run) {
  if (const std::string problem = options.Check(); !problem.empty()) throw InputError("suite", problem);
  const std::string& out = options.output_dir;
  CheckOutputFolder(out, {"suite.json", {"suite", "split", "bench", "runs"}, "suite"});
  CreateOutputFolder(out + "/runs");
  CreateOutputFolder(out + "/scenes");
  const nlohmann::json bench_json = BenchSettingsJson(bench);
  const std::vector<SuiteRunSpec> runs = SuiteRuns(suite, options.split);
  nlohmann::json marker = {{"suite", {{"name", suite.name}, {"file", SafeText(suite.path)}}},
                           {"split", options.split},
                           {"bench", bench_json},
                           {"runs", nlohmann::json::array()}};
  for (const SuiteRunSpec& run : runs) marker["runs"].push_back(run.name);
  WriteFileAtomic(out + "/suite.json", marker.dump(2) + "\n");

  const std::vector<std::string> methods = bench_json.at("methods").get<std::vector<std::string>>();
  std::vector<SuiteRunResult> results;
  for (size_t i = 0; i < runs.size(); ++i) {
    const SuiteRunSpec& run = runs[i];
    const SuiteSequence& seq = suite.sequences[run.sequence];
    const std::string dir = out + "/runs/" + run.name;
    SuiteRunResult result;
    result.name = run.name;
    try {
      const Scene scene = LoadRunScene(seq, run.seed, out);
      const RecordedRun recorded{
          dir, "suite_run.json", {{"sequence", seq.name}, {"seed", run.seed}, {"scene_hash", scene.hash}, {"bench", bench_json}}};
      const bool kept = recorded.Kept();
      if (before_run) before_run(static_cast<int>(i) + 1, static_cast<int>(runs.size()), run, kept);
      if (!kept) recorded.Run(scene, bench, options.run);
      const nlohmann::json report = nlohmann::json::parse(ReadFileBytes(dir + "/report.json"));
      for (const std::string& m : methods) {
        const nlohmann::json& method = report.at("methods").at(m);
        result.mrr[m] = Metric(method, "mrr");
        result.recall_at_1[m] = Metric(method, "recall_at_1");
      }
    } catch (const RenderInterrupted&) {
      throw;  // Ctrl-C stops the suite; a rerun resumes it
    } catch (const std::exception& e) {
      if (options.run.cancel != nullptr && options.run.cancel->load()) throw;  // stopped, not failed
      result = SuiteRunResult{run.name, e.what(), {}, {}};
      if (result.error.empty()) result.error = "failed without a message";
    }
    results.push_back(result);
  }
  SuiteSummary summary = SummariseSuite(suite.name, suite.description, methods, results);
  summary.settings = {{"split", options.split}, {"bench", bench_json}};
  WriteFileAtomic(out + "/suite_report.json", summary.ToJson().dump(2) + "\n");
  WriteFileAtomic(out + "/suite_report.md", summary.ToMarkdown());
  return summary;
}

}  // namespace hoilcd
