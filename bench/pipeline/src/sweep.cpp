#include "hoilcd/bench/pipeline/sweep.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "hoilcd/bench/methods/methods.h"
#include "hoilcd/bench/report/output_folder.h"
#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/folder_lock.h"
#include "hoilcd/core/util/json_reader.h"
#include "hoilcd/core/util/random.h"
#include "hoilcd/core/util/safe_text.h"
#include "hoilcd/core/util/text.h"
#include "hoilcd/sim/scene/scene.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

using Settings = std::vector<std::pair<std::string, std::string>>;

std::string Trim(const std::string& s) {
  const size_t b = s.find_first_not_of(" \t\n\r");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\n\r") - b + 1);
}

// Valid JSON is re-dumped compactly (" [1, 2]" and "[1,2]" name the same run); other text is a
// string value, as ApplyOverride takes it.
std::string CanonicalValue(const std::string& text) {
  const std::string t = Trim(text);
  const nlohmann::json value = ParseJsonOrDiscarded(t);
  return value.is_discarded() ? t : value.dump();
}

}  // namespace

std::string SweepSafeName(const std::string& s) {
  std::string out = s;
  for (char& c : out) {
    const bool ok = std::isalnum(static_cast<unsigned char>(c)) || std::string("._=,+-[]").find(c) != std::string::npos;
    if (!ok) c = '_';
  }
  return out;
}

std::string SweepSettingsName(const std::vector<std::pair<std::string, std::string>>& settings) {
  std::string out;
  for (const auto& [key, value] : settings) out += (out.empty() ? "" : ",") + key + "=" + value;
  return out;
}

nlohmann::json ReadSweepJson(const std::string& path) {
  std::string bytes;
  try {
    bytes = ReadFileBytes(path);
  } catch (const std::exception&) {
    throw InputError(path, "cannot read the file (is this a hoilcd sweep output folder?)");
  }
  return ParseJson(bytes, path);
}

std::vector<std::string> SplitTopLevelCommas(const std::string& text, const std::string& where) {
  std::vector<std::string> items;
  std::string current;
  std::vector<char> open;  // brackets still open, innermost last
  bool in_string = false, escaped = false;
  for (char c : text) {
    if (in_string) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      open.push_back(c == '[' ? ']' : '}');
    } else if (c == ']' || c == '}') {
      if (open.empty() || open.back() != c) {
        throw InputError(where, "unbalanced '" + std::string(1, c) + "' in '" + text + "'");
      }
      open.pop_back();
    } else if (c == ',' && open.empty()) {
      items.push_back(Trim(current));
      current.clear();
      continue;
    }
    current += c;
  }
  if (in_string) throw InputError(where, "unterminated string in '" + text + "'");
  if (!open.empty())
    throw InputError(where, "unclosed '" + std::string(1, open.back() == ']' ? '[' : '{') + "' in '" + text + "'");
  items.push_back(Trim(current));
  for (const std::string& item : items) {
    if (item.empty()) throw InputError(where, "empty value in '" + text + "' (values are separated by single commas)");
  }
  return items;
}

SweepAxis ParseSweepAxis(const std::string& key_equals_values) {
  const size_t eq = key_equals_values.find('=');
  if (eq == std::string::npos) {
    throw InputError("--set", "expected KEY=V1,V2,... but got '" + key_equals_values + "' (no '=')");
  }
  SweepAxis axis;
  axis.key = Trim(key_equals_values.substr(0, eq));
  if (axis.key.empty()) throw InputError("--set", "empty key in '" + key_equals_values + "'");
  if (axis.key == "seed" || axis.key == "/seed") {
    throw InputError("--set", "the seed is swept by --seeds N (seeds 1..N), not by --set");
  }
  std::set<std::string> seen;
  for (const std::string& v : SplitTopLevelCommas(key_equals_values.substr(eq + 1), "--set " + axis.key)) {
    const std::string value = CanonicalValue(v);
    if (!seen.insert(value).second) throw InputError("--set " + axis.key, "value " + value + " is listed twice");
    axis.values.push_back(value);
  }
  return axis;
}

std::string SweepRunSpec::Name() const {
  const std::string s = SweepSettingsName(settings);
  return s + (s.empty() ? "" : ",") + "seed=" + std::to_string(seed);
}

std::string SweepRunSpec::FolderName() const {
  const std::string safe = SweepSafeName(Name());
  if (safe.size() <= kMaxFolderName) return safe;
  char hash[18];
  std::snprintf(hash, sizeof hash, "~%016llx", static_cast<unsigned long long>(MixBits(HashString(Name()))));
  return safe.substr(0, kMaxFolderName - 17) + hash;
}

std::vector<std::string> SweepRunSpec::Overrides() const {
  std::vector<std::string> out;
  for (const auto& [key, value] : settings) out.push_back(key + "=" + value);
  out.push_back("seed=" + std::to_string(seed));
  return out;
}

nlohmann::json SweepRunSpec::ToJson() const {
  nlohmann::json s = nlohmann::json::array();
  for (const auto& [key, value] : settings) s.push_back({key, value});
  return {{"settings", s}, {"seed", seed}};
}

SweepRunSpec SweepRunSpec::FromJson(const nlohmann::json& j) {
  try {
    SweepRunSpec spec;
    for (const nlohmann::json& kv : j.at("settings"))
      spec.settings.emplace_back(kv.at(0).get<std::string>(), kv.at(1).get<std::string>());
    spec.seed = j.at("seed").get<int>();
    return spec;
  } catch (const nlohmann::json::exception& e) {
    throw InputError("sweep run", std::string("malformed run record (") + e.what() + ")");
  }
}

std::vector<Settings> SweepPlan::Combinations() const {
  std::vector<Settings> out = {{}};
  for (const SweepAxis& axis : axes) {
    std::vector<Settings> next;
    for (const Settings& prefix : out) {
      for (const std::string& value : axis.values) {
        Settings s = prefix;
        s.emplace_back(axis.key, value);
        next.push_back(s);
      }
    }
    out = next;
  }
  return out;
}

std::vector<SweepRunSpec> SweepPlan::Runs() const {
  std::vector<SweepRunSpec> runs;
  for (const Settings& s : Combinations()) {
    for (int seed = 1; seed <= seeds; ++seed) runs.push_back({s, seed});
  }
  std::sort(runs.begin(), runs.end(), [](const SweepRunSpec& a, const SweepRunSpec& b) { return a.Name() < b.Name(); });
  return runs;
}

std::vector<SweepRunSpec> SweepPlan::ShardRuns(const Shard& shard) const { return ShardOf(Runs(), shard); }

std::string SweepPlan::Check() const {
  if (scene_path.empty()) return "no scene file";
  if (seeds < 1) return "seeds must be at least 1";
  std::set<std::string> keys, folders;
  for (const SweepAxis& axis : axes) {
    if (axis.key.empty()) return "an axis has an empty key";
    if (axis.values.empty()) return "axis " + axis.key + " has no values";
    if (!keys.insert(axis.key).second) return "key " + axis.key + " is swept twice";
  }
  // Counted before the runs are listed: a cross product of long --set lists would not fit memory.
  // Each run renders and benches a dataset (minutes); 100,000 of them are years of one machine.
  constexpr double kMaxRuns = 100000;
  double runs = seeds;
  for (const SweepAxis& axis : axes) runs *= static_cast<double>(axis.values.size());
  if (runs > kMaxRuns) {
    std::string product;
    for (const SweepAxis& axis : axes) product += std::to_string(axis.values.size()) + " values of " + axis.key + " x ";
    return product + std::to_string(seeds) + " seeds is " + Fixed(runs, 0) + " runs; at most " + Fixed(kMaxRuns, 0) +
           " (split a larger study into several sweeps)";
  }
  for (const SweepRunSpec& run : Runs()) {
    if (!folders.insert(run.FolderName()).second) return "two runs share the folder name " + run.FolderName();
  }
  return "";
}

nlohmann::json SweepPlan::ToJson() const {
  nlohmann::json a = nlohmann::json::array();
  for (const SweepAxis& axis : axes) a.push_back({{"key", axis.key}, {"values", axis.values}});
  return {{"scene_path", SafeText(scene_path)},
          {"scene_name", scene_name},
          {"scene_hash", scene_hash},
          {"axes", a},
          {"seeds", seeds},
          {"bench", bench}};
}

SweepPlan SweepPlan::FromJson(const nlohmann::json& j, const std::string& where) {
  try {
    SweepPlan plan;
    plan.scene_path = j.at("scene_path").get<std::string>();
    plan.scene_name = j.at("scene_name").get<std::string>();
    plan.scene_hash = j.at("scene_hash").get<std::string>();
    for (const nlohmann::json& a : j.at("axes")) {
      plan.axes.push_back({a.at("key").get<std::string>(), a.at("values").get<std::vector<std::string>>()});
    }
    plan.seeds = j.at("seeds").get<int>();
    plan.bench = j.at("bench");
    if (const std::string problem = plan.Check(); !problem.empty()) throw InputError(where, problem);
    return plan;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(where, std::string("malformed sweep plan (") + e.what() + ")");
  }
}

SweepPlan MakeSweepPlan(const std::string& scene_path, const std::vector<std::string>& sets, int seeds,
                        const BenchOptions& bench) {
  if (seeds < 1) throw InputError("--seeds", "must be at least 1 (seeds 1..N are run)");
  SweepPlan plan;
  plan.scene_path = scene_path;
  const Scene base = LoadScene(scene_path);
  plan.scene_name = base.name;
  plan.scene_hash = base.hash;
  plan.seeds = seeds;
  plan.bench = BenchSettingsJson(bench);
  for (const std::string& set : sets) plan.axes.push_back(ParseSweepAxis(set));
  if (const std::string problem = plan.Check(); !problem.empty()) throw InputError("--set", problem);
  for (const Settings& s : plan.Combinations()) {
    try {
      LoadScene(scene_path, SweepRunSpec{s, 1}.Overrides());
    } catch (const InputError& e) {
      throw InputError("--set", "the combination " + (s.empty() ? "(none)" : SweepSettingsName(s)) +
                                    " does not give a valid scene:\n" + e.what());
    }
  }
  return plan;
}

SweepOptions::SweepOptions() { Table().FillDefaults(this); }

const OptionTable<SweepOptions>& SweepOptions::Table() {
  using O = SweepOptions;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("output_dir", &O::output_dir, "", {}, "runs/<FolderName>/ and sweep.json (the shard marker) go here")
          .Rule("output_dir", [](const O& o) { return o.output_dir.empty() ? "the output folder must be given" : ""; })
          .Rule("shard", [](const O& o) { return o.shard.Check(); })
          .Nest("run", &O::run, RunOptions::Table());
  return table;
}

std::string SweepOptions::Check() const { return Table().FirstProblem(*this); }

void RunSweep(const SweepPlan& plan, const BenchOptions& bench, const SweepOptions& options,
              const SweepRunCallback& before_run) {
  if (const std::string problem = options.Check(); !problem.empty()) throw InputError("sweep", problem);
  if (const std::string problem = plan.Check(); !problem.empty()) throw InputError("sweep", problem);
  HOILCD_CHECK_MSG(BenchSettingsJson(bench) == plan.bench, "the plan was made with other bench options");
  // A folder of the user's is refused before any work: only an earlier sweep (sweep.json) is ours.
  CheckOutputFolder(options.output_dir, {"sweep.json", {"plan", "shard", "runs"}, "sweep"});
  const FolderLock lock(options.output_dir, FolderLock::IfBusy::kRefuse);  // one sweep at a time in a folder
  std::error_code ec;
  fs::create_directories(options.output_dir + "/runs", ec);
  if (ec) throw InputError(options.output_dir, "cannot create the sweep folder (" + ec.message() + ")");

  const std::vector<SweepRunSpec> runs = plan.ShardRuns(options.shard);
  nlohmann::json marker = {{"plan", plan.ToJson()},
                           {"shard", {{"index", options.shard.index}, {"count", options.shard.count}}},
                           {"runs", nlohmann::json::array()},
                           {"finished", false}};
  for (const SweepRunSpec& run : runs) marker["runs"].push_back(run.ToJson());
  WriteFileAtomic(options.output_dir + "/sweep.json", marker.dump(2));

  for (size_t i = 0; i < runs.size(); ++i) {
    const SweepRunSpec& run = runs[i];
    const Scene scene = LoadScene(plan.scene_path, run.Overrides());
    const std::string dir = options.output_dir + "/runs/" + run.FolderName();
    const RecordedRun recorded{
        dir, "sweep_run.json", {{"run", run.ToJson()}, {"scene_hash", scene.hash}, {"bench", plan.bench}}};
    const bool kept = recorded.Kept();
    if (before_run) before_run(static_cast<int>(i) + 1, static_cast<int>(runs.size()), run, kept);
    if (!kept) recorded.Run(scene, bench, options.run);
  }
  marker["finished"] = true;
  WriteFileAtomic(options.output_dir + "/sweep.json", marker.dump(2));
}

}  // namespace hoilcd
