#include "hoilcd/bench/pipeline/suite.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <set>

#include "hoilcd/bench/evaluation/safe_text.h"
#include "hoilcd/bench/report/output_folder.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/file_io.h"
#include "hoilcd/core/util/json_reader.h"
#include "hoilcd/sim/generate/generator.h"
#include "hoilcd/sim/output/sequence.h"
#include "hoilcd/sim/scene/scene.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

bool SafeName(const std::string& name) {
  if (name.empty() || name.size() > 100 || name[0] == '.') return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-';
  });
}

void ReadSequence(JsonReader* r, const nlohmann::json& j, const std::string& ptr, const fs::path& base,
                  SuiteSequence* s) {
  if (!r->ExpectObject(j, ptr)) return;
  r->CheckKeys(j, ptr, {"name", "scene", "generate", "seeds", "set", "split"});
  r->Read(j, ptr, "name", &s->name);
  if (j.contains("name") && j["name"].is_string() && !SafeName(s->name)) {
    r->Add(ptr + "/name", "expected 1-100 letters, digits, '.', '_' or '-' (not starting with '.'): it names the run folders");
  }
  const bool has_scene = j.contains("scene"), has_generate = j.contains("generate");
  if (has_scene == has_generate) {
    r->Add(ptr, "expected exactly one of \"scene\" (a scene file) and \"generate\" (a generator spec)");
  } else if (has_scene) {
    std::string scene;
    r->Read(j, ptr, "scene", &scene);
    if (j["scene"].is_string() && scene.empty()) r->Add(ptr + "/scene", "expected a scene file path, got \"\"");
    if (!scene.empty()) s->scene_path = fs::path(scene).is_absolute() ? scene : (base / scene).lexically_normal().string();
  } else {
    const std::string gptr = ptr + "/generate";
    const nlohmann::json& g = j["generate"];
    s->generated = true;
    if (r->ExpectObject(g, gptr)) {
      r->CheckKeys(g, gptr, {"layout", "seed", "index"});
      r->Read(g, gptr, "layout", &s->layout);
      const std::vector<std::string>& families = LayoutFamilies();
      if (g.contains("layout") && g["layout"].is_string() && s->layout != "mixed" &&
          std::find(families.begin(), families.end(), s->layout) == families.end()) {
        std::string list;
        for (const std::string& f : families) list += f + ", ";
        r->Add(gptr + "/layout", "expected a layout family (" + list + "or mixed), got \"" + SafeText(s->layout) + "\"");
      }
      r->Read(g, gptr, "seed", &s->generator_seed);
      r->Read(g, gptr, "index", &s->generator_index);
      if (s->generator_index < 0) r->Add(gptr + "/index", "expected a non-negative integer");
    }
  }
  const std::string sptr = ptr + "/seeds";
  if (!j.contains("seeds")) {
    r->Add(sptr, "missing");
  } else if (r->ExpectArray(j["seeds"], sptr)) {
    if (j["seeds"].empty()) r->Add(sptr, "expected at least one seed");
    std::set<int> seen;
    for (size_t k = 0; k < j["seeds"].size(); ++k) {
      int seed = -1;
      r->ReadValue(j["seeds"][k], sptr + "/" + std::to_string(k), &seed);
      if (j["seeds"][k].is_number_integer() && seed < 0) {
        r->Add(sptr + "/" + std::to_string(k), "expected a non-negative seed");
      } else if (seed >= 0 && !seen.insert(seed).second) {
        r->Add(sptr + "/" + std::to_string(k), "seed " + std::to_string(seed) + " is listed twice");
      }
      if (seed >= 0) s->seeds.push_back(seed);
    }
  }
  if (j.contains("set") && r->ExpectArray(j["set"], ptr + "/set")) {
    for (size_t k = 0; k < j["set"].size(); ++k) {
      const std::string where = ptr + "/set/" + std::to_string(k);
      std::string set;
      r->ReadValue(j["set"][k], where, &set);
      if (!j["set"][k].is_string()) continue;
      const size_t eq = set.find('=');
      const std::string key = set.substr(0, eq);
      if (eq == std::string::npos || eq == 0) {
        r->Add(where, "expected \"key=value\", got \"" + SafeText(set) + "\"");
      } else if (key == "seed" || key == "/seed") {
        r->Add(where, "the seed is given by \"seeds\", not by \"set\"");
      } else {
        s->sets.push_back(set);
      }
    }
  }
  r->Read(j, ptr, "split", &s->split);
  if (j.contains("split") && j["split"].is_string() && s->split != "dev" && s->split != "test") {
    r->Add(ptr + "/split", "expected \"dev\" or \"test\", got \"" + SafeText(s->split) + "\"");
  }
}

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

Suite ParseSuite(const std::string& text, const std::string& path) {
  JsonReader r(path);
  const nlohmann::json j = r.Parse(text);
  Suite suite;
  suite.path = path;
  if (r.ExpectObject(j, "")) {
    r.CheckKeys(j, "", {"name", "description", "sequences"});
    r.Read(j, "", "name", &suite.name);
    if (j.contains("description")) r.ReadValue(j["description"], "/description", &suite.description);
    if (!j.contains("sequences")) {
      r.Add("/sequences", "missing");
    } else if (r.ExpectArray(j["sequences"], "/sequences")) {
      if (j["sequences"].empty()) r.Add("/sequences", "expected at least one sequence");
      const fs::path base = fs::path(path).parent_path();
      std::set<std::string> names;
      for (size_t k = 0; k < j["sequences"].size(); ++k) {
        const std::string ptr = "/sequences/" + std::to_string(k);
        SuiteSequence s;
        ReadSequence(&r, j["sequences"][k], ptr, base, &s);
        if (!s.name.empty() && !names.insert(s.name).second) r.Add(ptr + "/name", "sequence name \"" + s.name + "\" is used twice");
        suite.sequences.push_back(s);
      }
    }
  }
  r.problems().ThrowIfAny();
  return suite;
}

Suite ReadSuite(const std::string& path) {
  std::string text;
  try {
    text = ReadFileBytes(path, 16u << 20);  // a suite lists sequences: megabytes are a mistake
  } catch (const InputError& e) {
    throw InputError(path, std::string("cannot read the suite file: ") + e.what());
  }
  return ParseSuite(text, path);
}

std::vector<SuiteRunSpec> SuiteRuns(const Suite& suite, const std::string& split) {
  std::vector<SuiteRunSpec> runs;
  for (size_t k = 0; k < suite.sequences.size(); ++k) {
    const SuiteSequence& s = suite.sequences[k];
    if (split != "all" && s.split != split) continue;
    for (int seed : s.seeds) runs.push_back({k, seed, s.name + "-seed" + std::to_string(seed)});
  }
  std::sort(runs.begin(), runs.end(), [](const SuiteRunSpec& a, const SuiteRunSpec& b) { return a.name < b.name; });
  return runs;
}

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
      const nlohmann::json record = {{"sequence", seq.name}, {"seed", run.seed}, {"scene_hash", scene.hash}, {"bench", bench_json}};
      const std::string record_path = dir + "/suite_run.json";
      bool kept = false;
      std::error_code ec;
      if (fs::exists(record_path, ec) && fs::exists(dir + "/report.json", ec)) {
        try {
          kept = nlohmann::json::parse(ReadFileBytes(record_path)) == record;
        } catch (const std::exception&) {
          kept = false;  // unreadable: run again
        }
      }
      if (before_run) before_run(static_cast<int>(i) + 1, static_cast<int>(runs.size()), run, kept);
      if (!kept) {
        fs::remove(record_path, ec);  // an interrupted rerun must not leave the old record
        RunOptions r = options.run;
        r.report_dir = dir;
        RunScene(scene, bench, r);
        WriteFileAtomic(record_path, record.dump(2) + "\n");
      }
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
