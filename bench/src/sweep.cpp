#include "hoilcd/bench/sweep.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "hoilcd/bench/chart.h"
#include "hoilcd/bench/methods.h"
#include "hoilcd/core/dataset.h"
#include "hoilcd/core/error.h"
#include "hoilcd/sim/scene.h"

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
  if (nlohmann::json::accept(t)) return nlohmann::json::parse(t).dump();
  return t;
}

std::string SafeForPath(const std::string& s) {
  std::string out = s;
  for (char& c : out) {
    const bool ok = std::isalnum(static_cast<unsigned char>(c)) || std::string("._=,+-[]").find(c) != std::string::npos;
    if (!ok) c = '_';
  }
  return out;
}

std::string SettingsName(const Settings& settings) {
  std::string out;
  for (const auto& [key, value] : settings) out += (out.empty() ? "" : ",") + key + "=" + value;
  return out;
}

std::string Fixed(double v, int digits) {
  if (!std::isfinite(v)) return "-";
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.*f", digits, v);
  return buf;
}

int Digits(const SweepMetric& metric) { return metric.key == "ms_per_query" ? 2 : 3; }

std::string CsvField(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string CsvNumber(double v) {
  if (!std::isfinite(v)) return "";
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.6g", v);
  return buf;
}

nlohmann::json ReadJson(const std::string& path) {
  std::string bytes;
  try {
    bytes = ReadFileBytes(path);
  } catch (const std::exception&) {
    throw InputError(path, "cannot read the file (is this a hoilcd sweep output folder?)");
  }
  try {
    return nlohmann::json::parse(bytes);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path, std::string("not valid JSON (") + e.what() + ")");
  }
}

double JsonMetric(const nlohmann::json& method, const std::string& key) {
  const auto it = method.find(key);
  return it != method.end() && it->is_number() ? it->get<double>() : NAN;
}

// Where two plans first differ, as a JSON pointer (the first operation of their JSON Patch).
std::string FirstDifference(const nlohmann::json& a, const nlohmann::json& b) {
  const nlohmann::json patch = nlohmann::json::diff(a, b);
  return patch.empty() ? "" : patch.front().value("path", "");
}

// What shards of one sweep share: the plan without the scene path (the same scene file may sit
// at another path on another machine; its hash says whether it is the same scene).
nlohmann::json Identity(const SweepPlan& plan) {
  nlohmann::json j = plan.ToJson();
  j.erase("scene_path");
  return j;
}

}  // namespace

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
  if (!open.empty()) throw InputError(where, "unclosed '" + std::string(1, open.back() == ']' ? '[' : '{') + "' in '" + text + "'");
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

std::string SweepShard::Check() const {
  if (count < 1) return "the number of shards must be at least 1";
  if (index < 0 || index >= count) return "the shard index must be in 0.." + std::to_string(count - 1);
  return "";
}

SweepShard ParseSweepShard(const std::string& text) {
  const size_t slash = text.find('/');
  auto parse = [&](const std::string& part) {
    const std::string t = Trim(part);
    if (t.empty() || t.find_first_not_of("0123456789") != std::string::npos || t.size() > 9) {
      throw InputError("--shard", "expected I/N with whole numbers, 0 <= I < N (e.g. 0/4), but got '" + text + "'");
    }
    return std::stoi(t);
  };
  if (slash == std::string::npos) parse("");
  SweepShard shard;
  shard.index = parse(text.substr(0, slash));
  shard.count = parse(text.substr(slash + 1));
  if (const std::string problem = shard.Check(); !problem.empty()) throw InputError("--shard", problem + " (got '" + text + "')");
  return shard;
}

std::string SweepRunSpec::Name() const {
  const std::string s = SettingsName(settings);
  return s + (s.empty() ? "" : ",") + "seed=" + std::to_string(seed);
}

std::string SweepRunSpec::FolderName() const { return SafeForPath(Name()); }

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
    for (const nlohmann::json& kv : j.at("settings")) spec.settings.emplace_back(kv.at(0).get<std::string>(), kv.at(1).get<std::string>());
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

std::vector<SweepRunSpec> SweepPlan::ShardRuns(const SweepShard& shard) const {
  HOILCD_CHECK_MSG(shard.Check().empty(), shard.Check());
  const std::vector<SweepRunSpec> all = Runs();
  std::vector<SweepRunSpec> out;
  for (size_t k = static_cast<size_t>(shard.index); k < all.size(); k += static_cast<size_t>(shard.count)) out.push_back(all[k]);
  return out;
}

std::string SweepPlan::Check() const {
  if (scene_path.empty()) return "no scene file";
  if (seeds < 1) return "seeds must be at least 1";
  std::set<std::string> keys, folders;
  for (const SweepAxis& axis : axes) {
    if (axis.key.empty()) return "an axis has an empty key";
    if (axis.values.empty()) return "axis " + axis.key + " has no values";
    if (!keys.insert(axis.key).second) return "key " + axis.key + " is swept twice";
  }
  for (const SweepRunSpec& run : Runs()) {
    if (!folders.insert(run.FolderName()).second) return "two runs share the folder name " + run.FolderName();
  }
  return "";
}

nlohmann::json SweepPlan::ToJson() const {
  nlohmann::json a = nlohmann::json::array();
  for (const SweepAxis& axis : axes) a.push_back({{"key", axis.key}, {"values", axis.values}});
  return {{"scene_path", scene_path}, {"scene_name", scene_name}, {"scene_hash", scene_hash},
          {"axes", a}, {"seeds", seeds}, {"bench", bench}};
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

nlohmann::json SweepBenchJson(const BenchOptions& options) {
  const std::vector<std::string> methods = options.methods.empty() ? DefaultMethods() : options.methods;
  return {{"methods", methods},
          {"protocol", options.protocol.protocol},
          {"radius_m", options.protocol.radius_m},
          {"exclusion_window_s", options.protocol.exclusion_window_s},
          {"heading_tolerance_deg", options.protocol.heading_tolerance_deg},
          {"ground_truth", options.protocol.ground_truth},
          {"keypoint_detector", options.keypoints.detector},
          {"rrf_k", options.rrf_k}};
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
  plan.bench = SweepBenchJson(bench);
  for (const std::string& set : sets) plan.axes.push_back(ParseSweepAxis(set));
  if (const std::string problem = plan.Check(); !problem.empty()) throw InputError("--set", problem);
  for (const Settings& s : plan.Combinations()) {
    try {
      LoadScene(scene_path, SweepRunSpec{s, 1}.Overrides());
    } catch (const InputError& e) {
      throw InputError("--set", "the combination " + (s.empty() ? "(none)" : SettingsName(s)) +
                                    " does not give a valid scene:\n" + e.what());
    }
  }
  return plan;
}

std::string SweepOptions::Check() const {
  if (output_dir.empty()) return "the output folder must be given";
  if (const std::string problem = shard.Check(); !problem.empty()) return problem;
  return run.Check();
}

void RunSweep(const SweepPlan& plan, const BenchOptions& bench, const SweepOptions& options,
              const SweepRunCallback& before_run) {
  if (const std::string problem = options.Check(); !problem.empty()) throw InputError("sweep", problem);
  if (const std::string problem = plan.Check(); !problem.empty()) throw InputError("sweep", problem);
  HOILCD_CHECK_MSG(SweepBenchJson(bench) == plan.bench, "the plan was made with other bench options");
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
    const nlohmann::json record = {{"run", run.ToJson()}, {"scene_hash", scene.hash}, {"bench", plan.bench}};
    const std::string record_path = dir + "/sweep_run.json";
    bool kept = false;
    if (fs::exists(record_path, ec) && fs::exists(dir + "/report.json", ec)) {
      try {
        kept = ReadJson(record_path) == record;
      } catch (const InputError&) {
        kept = false;  // unreadable: run again
      }
    }
    if (before_run) before_run(static_cast<int>(i) + 1, static_cast<int>(runs.size()), run, kept);
    if (kept) continue;
    fs::remove(record_path, ec);  // an interrupted rerun must not leave the old record
    RunOptions r = options.run;
    r.report_dir = dir;
    RunScene(scene, bench, r);
    WriteFileAtomic(record_path, record.dump(2));
  }
  marker["finished"] = true;
  WriteFileAtomic(options.output_dir + "/sweep.json", marker.dump(2));
}

SweepStats SweepStats::Of(const std::vector<double>& values) {
  SweepStats s;
  double sum = 0;
  for (double v : values) {
    if (!std::isfinite(v)) continue;
    ++s.count;
    sum += v;
    s.min = s.count == 1 ? v : std::min(s.min, v);
    s.max = s.count == 1 ? v : std::max(s.max, v);
  }
  if (s.count == 0) return s;
  s.mean = sum / s.count;
  double squares = 0;
  for (double v : values) {
    if (std::isfinite(v)) squares += (v - s.mean) * (v - s.mean);
  }
  s.std = s.count > 1 ? std::sqrt(squares / (s.count - 1)) : 0.0;
  return s;
}

const std::vector<SweepMetric>& SweepMetrics() {
  static const std::vector<SweepMetric> kMetrics = {
      {"mrr", "MRR"},       {"recall_at_1", "R@1"},         {"recall_at_5", "R@5"},
      {"pr_auc", "PR-AUC"}, {"recall_at_100p", "R@100%P"}, {"ms_per_query", "ms/query"}};
  return kMetrics;
}

SweepSummary MergeSweep(const std::vector<std::string>& dirs, const SweepPlan* expected) {
  if (dirs.empty()) throw InputError("--merge", "no sweep output folders given");
  struct Found {
    std::string dir;
    SweepRunSpec spec;
  };
  std::optional<SweepPlan> plan;
  std::string plan_source;
  if (expected) {
    plan = *expected;
    plan_source = "the command line";
  }
  std::map<std::string, std::vector<Found>> found;  // by run name: completed copies
  std::map<std::string, std::string> unfinished;    // run name -> why its report is missing
  std::vector<Problem> problems;
  for (const std::string& dir : dirs) {
    const std::string marker_path = dir + "/sweep.json";
    const nlohmann::json marker = ReadJson(marker_path);
    if (!marker.contains("plan") || !marker.contains("runs") || !marker.contains("shard")) {
      throw InputError(marker_path, "not a sweep marker (needs plan, shard and runs)");
    }
    const SweepPlan dir_plan = SweepPlan::FromJson(marker.at("plan"), marker_path);
    if (!plan) {
      plan = dir_plan;
      plan_source = marker_path;
    } else if (Identity(dir_plan) != Identity(*plan)) {
      throw InputError(marker_path, "its sweep differs from the one in " + plan_source + " at " +
                                        FirstDifference(Identity(dir_plan), Identity(*plan)) +
                                        " (shards of one sweep must be run with the same scene, --set, --seeds and bench flags)");
    }
    const std::string shard = std::to_string(marker["shard"].value("index", 0)) + "/" +
                              std::to_string(marker["shard"].value("count", 1));
    for (const nlohmann::json& r : marker.at("runs")) {
      const SweepRunSpec spec = SweepRunSpec::FromJson(r);
      const std::string run_dir = dir + "/runs/" + spec.FolderName();
      std::error_code ec;
      if (fs::exists(run_dir + "/sweep_run.json", ec) && fs::exists(run_dir + "/report.json", ec)) {
        found[spec.Name()].push_back({dir, spec});
      } else {
        unfinished[spec.Name()] = "shard " + shard + " in " + dir + " has no finished report in " + run_dir +
                                  (marker.value("finished", false) ? "" : "; that shard did not finish");
      }
    }
  }

  std::set<std::string> expected_names;
  for (const SweepRunSpec& run : plan->Runs()) {
    expected_names.insert(run.Name());
    const auto it = found.find(run.Name());
    if (it == found.end()) {
      const auto why = unfinished.find(run.Name());
      problems.push_back({"--merge", "missing run " + run.Name() +
                                         (why != unfinished.end() ? " (" + why->second + ")" : " (in no shard's run list)")});
    } else if (it->second.size() > 1) {
      std::string where;
      for (const Found& f : it->second) where += (where.empty() ? "" : ", ") + f.dir;
      problems.push_back({"--merge", "run " + run.Name() + " appears " + std::to_string(it->second.size()) +
                                         " times (in " + where + ")"});
    }
  }
  for (const auto& [name, copies] : found) {
    if (!expected_names.count(name)) {
      problems.push_back({"--merge", "run " + name + " in " + copies.front().dir + " is not part of the sweep"});
    }
  }
  if (!problems.empty()) throw InputError(problems);

  const std::vector<std::string> methods = plan->bench.at("methods").get<std::vector<std::string>>();
  const std::vector<SweepMetric>& metrics = SweepMetrics();
  // values[combination name][method][metric] over seeds
  std::map<std::string, std::vector<std::vector<std::vector<double>>>> values;
  std::map<std::string, std::vector<int>> seeds;
  for (const auto& [name, copies] : found) {
    const Found& f = copies.front();
    const std::string path = f.dir + "/runs/" + f.spec.FolderName() + "/report.json";
    const nlohmann::json report = ReadJson(path);
    const std::string combo = SettingsName(f.spec.settings);
    auto& v = values[combo];
    v.resize(methods.size(), std::vector<std::vector<double>>(metrics.size()));
    seeds[combo].push_back(f.spec.seed);
    for (size_t m = 0; m < methods.size(); ++m) {
      if (!report.contains("methods") || !report["methods"].contains(methods[m])) {
        throw InputError(path, "has no results of method " + methods[m]);
      }
      for (size_t k = 0; k < metrics.size(); ++k) v[m][k].push_back(JsonMetric(report["methods"][methods[m]], metrics[k].key));
    }
  }

  SweepSummary summary;
  summary.plan = *plan;
  for (const Settings& s : plan->Combinations()) {
    const std::string combo = SettingsName(s);
    std::vector<int> seed_list = seeds[combo];
    std::sort(seed_list.begin(), seed_list.end());
    for (size_t m = 0; m < methods.size(); ++m) {
      SweepSummaryRow row;
      row.settings = s;
      row.method = methods[m];
      row.seeds = seed_list;
      for (size_t k = 0; k < metrics.size(); ++k) row.stats.push_back(SweepStats::Of(values[combo][m][k]));
      summary.rows.push_back(row);
    }
  }
  return summary;
}

std::string SweepSummary::ToCsv() const {
  std::ostringstream out;
  for (const SweepAxis& axis : plan.axes) out << CsvField(axis.key) << ",";
  out << "method,seeds";
  for (const SweepMetric& metric : SweepMetrics()) {
    for (const char* stat : {"mean", "std", "min", "max"}) out << "," << metric.key << "_" << stat;
  }
  out << "\n";
  for (const SweepSummaryRow& row : rows) {
    for (const auto& [key, value] : row.settings) out << CsvField(value) << ",";
    out << row.method << "," << row.seeds.size();
    for (const SweepStats& s : row.stats) {
      out << "," << CsvNumber(s.mean) << "," << CsvNumber(s.std) << "," << CsvNumber(s.min) << "," << CsvNumber(s.max);
    }
    out << "\n";
  }
  return out.str();
}

std::string SweepSummary::ToMarkdown() const {
  const std::vector<SweepMetric>& metrics = SweepMetrics();
  std::ostringstream out;
  out << "# hoilcd sweep of " << plan.scene_name << "\n\n"
      << "Scene `" << plan.scene_path << "` (hash `" << plan.scene_hash << "`), seeds 1.." << plan.seeds
      << ", methods " << plan.bench.at("methods").dump() << ", protocol `" << plan.bench.value("protocol", "")
      << "`. Each cell: mean ± sample std [min, max] over the seeds. Every run's report is in runs/.\n\n|";
  for (const SweepAxis& axis : plan.axes) out << " `" << axis.key << "` |";
  out << " method | seeds |";
  for (const SweepMetric& metric : metrics) out << " " << metric.label << " |";
  out << "\n|";
  for (size_t i = 0; i < plan.axes.size() + 2 + metrics.size(); ++i) out << "---|";
  out << "\n";
  for (const SweepSummaryRow& row : rows) {
    out << "|";
    for (const auto& [key, value] : row.settings) out << " " << value << " |";
    out << " " << row.method << " | " << row.seeds.size() << " |";
    for (size_t k = 0; k < metrics.size(); ++k) {
      const SweepStats& s = row.stats[k];
      const int d = Digits(metrics[k]);
      out << " " << Fixed(s.mean, d) << " ± " << Fixed(s.std, d) << " [" << Fixed(s.min, d) << ", " << Fixed(s.max, d) << "] |";
    }
    out << "\n";
  }
  return out.str();
}

std::string SweepSummary::FormatTable() const {
  const std::vector<SweepMetric>& metrics = SweepMetrics();
  std::vector<std::vector<std::string>> table;
  std::vector<std::string> header;
  for (const SweepAxis& axis : plan.axes) header.push_back(axis.key);
  header.push_back("method");
  for (const SweepMetric& metric : metrics) header.push_back(metric.label);
  table.push_back(header);
  for (const SweepSummaryRow& row : rows) {
    std::vector<std::string> line;
    for (const auto& [key, value] : row.settings) line.push_back(value);
    line.push_back(row.method);
    for (size_t k = 0; k < metrics.size(); ++k) {
      const int d = Digits(metrics[k]);
      line.push_back(Fixed(row.stats[k].mean, d) + "±" + Fixed(row.stats[k].std, d));
    }
    table.push_back(line);
  }
  std::vector<size_t> width(header.size(), 0);
  for (const auto& line : table)
    for (size_t c = 0; c < line.size(); ++c) width[c] = std::max(width[c], line[c].size());
  std::ostringstream out;
  for (const auto& line : table) {
    for (size_t c = 0; c < line.size(); ++c) {
      const bool left = c <= plan.axes.size();
      const std::string pad(width[c] - line[c].size(), ' ');
      out << (c ? "  " : "") << (left ? line[c] + pad : pad + line[c]);
    }
    out << "\n";
  }
  out << "mean±std over seeds 1.." << plan.seeds << "; min and max in summary.csv\n";
  return out.str();
}

void WriteSweepSummary(const SweepSummary& summary, const std::string& out_dir) {
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) throw InputError(out_dir, "cannot create the sweep folder (" + ec.message() + ")");
  WriteFileAtomic(out_dir + "/summary.csv", summary.ToCsv());
  std::string md = summary.ToMarkdown();

  const std::vector<SweepMetric>& metrics = SweepMetrics();
  const std::vector<SweepAxis>& axes = summary.plan.axes;
  std::vector<std::string> figures;
  for (size_t a = 0; a < axes.size(); ++a) {
    const SweepAxis& axis = axes[a];
    if (axis.values.size() < 2) continue;
    // Numeric values are the abscissae; otherwise their position in the list is.
    bool numeric = true;
    for (const std::string& v : axis.values) numeric = numeric && nlohmann::json::parse(v, nullptr, false).is_number();
    std::vector<double> x_of(axis.values.size());
    std::string x_label = axis.key;
    for (size_t i = 0; i < axis.values.size(); ++i) {
      x_of[i] = numeric ? nlohmann::json::parse(axis.values[i]).get<double>() : static_cast<double>(i);
      if (!numeric) x_label += (i ? ", " : " (") + std::to_string(i) + " = " + axis.values[i];
    }
    if (!numeric) x_label += ")";
    for (size_t k = 0; k < metrics.size(); ++k) {
      // One series per method and combination of the other axes' values.
      std::map<std::string, Series> series_by_label;
      std::vector<std::string> order;
      for (const SweepSummaryRow& row : summary.rows) {
        std::string others;
        for (size_t b = 0; b < axes.size(); ++b) {
          if (b != a && axes[b].values.size() > 1) others += (others.empty() ? "" : ",") + row.settings[b].first + "=" + row.settings[b].second;
        }
        const std::string label = row.method + (others.empty() ? "" : " " + others);
        if (!series_by_label.count(label)) order.push_back(label);
        Series& s = series_by_label[label];
        s.label = label;
        const size_t vi = static_cast<size_t>(std::find(axis.values.begin(), axis.values.end(), row.settings[a].second) - axis.values.begin());
        s.x.push_back(x_of[vi]);
        s.y.push_back(row.stats[k].mean);
        s.y_low.push_back(row.stats[k].min);
        s.y_high.push_back(row.stats[k].max);
      }
      std::vector<Series> series;
      for (const std::string& label : order) {
        Series s = series_by_label[label];
        std::vector<size_t> idx(s.x.size());
        for (size_t i = 0; i < idx.size(); ++i) idx[i] = i;
        std::sort(idx.begin(), idx.end(), [&](size_t p, size_t q) { return s.x[p] < s.x[q]; });
        Series sorted = s;
        for (size_t i = 0; i < idx.size(); ++i) {
          sorted.x[i] = s.x[idx[i]];
          sorted.y[i] = s.y[idx[i]];
          sorted.y_low[i] = s.y_low[idx[i]];
          sorted.y_high[i] = s.y_high[idx[i]];
        }
        sorted.band = true;
        sorted.markers = true;
        series.push_back(sorted);
      }
      PlotOptions o;
      o.title = metrics[k].label + " vs " + axis.key + " (mean of seeds 1.." + std::to_string(summary.plan.seeds) +
                ", band min-max)";
      o.x_label = x_label;
      o.y_label = metrics[k].label;
      const std::string name = "plot_" + SafeForPath(axis.key) + "_" + metrics[k].key + ".png";
      WritePng(out_dir + "/" + name, LinePlot(series, o));
      figures.push_back(name);
    }
  }
  if (!figures.empty()) {
    md += "\n## Plots\n\n";
    for (const std::string& f : figures) md += "![" + f + "](" + f + ")\n\n";
  }
  WriteFileAtomic(out_dir + "/summary.md", md);
}

}  // namespace hoilcd
