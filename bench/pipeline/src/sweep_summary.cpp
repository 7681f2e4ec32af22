#include "hoilcd/bench/pipeline/sweep_summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "hoilcd/bench/evaluation/json_number.h"
#include "hoilcd/bench/report/chart.h"
#include "hoilcd/bench/report/output_folder.h"
#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/dataset/dataset_folder.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/file_io.h"
#include "hoilcd/core/util/folder_lock.h"
#include "hoilcd/core/util/json_reader.h"
#include "hoilcd/core/util/safe_text.h"
#include "hoilcd/core/util/stats.h"
#include "hoilcd/core/util/text.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

using Settings = std::vector<std::pair<std::string, std::string>>;

int Digits(const SweepMetric& metric) { return metric.key == "ms_per_query" ? 2 : 3; }

std::string CsvField(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// What shards of one sweep share: the plan without the scene path (the same scene file may sit
// at another path on another machine; its hash says whether it is the same scene).
nlohmann::json Identity(const SweepPlan& plan) {
  nlohmann::json j = plan.ToJson();
  j.erase("scene_path");
  return j;
}

}  // namespace

SweepStats SweepStats::Of(const std::vector<double>& values) {
  std::vector<double> finite;
  for (double v : values)
    if (std::isfinite(v)) finite.push_back(v);
  SweepStats s;
  s.count = static_cast<int>(finite.size());
  if (finite.empty()) return s;
  s.mean = Mean(finite);
  s.std = StdDev(finite);
  s.min = *std::min_element(finite.begin(), finite.end());
  s.max = *std::max_element(finite.begin(), finite.end());
  return s;
}

const std::vector<SweepMetric>& SweepMetrics() {
  static const std::vector<SweepMetric> kMetrics = {
      {"mrr", "MRR"},       {"recall_at_1", "R@1"},        {"recall_at_5", "R@5"},
      {"pr_auc", "PR-AUC"}, {"recall_at_100p", "R@100%P"}, {"ms_per_query", "ms/query"}};
  return kMetrics;
}

namespace {

// What the shard folders of a sweep hold: its plan, and each run's finished copies.
struct ShardContents {
  struct Copy {
    std::string dir;
    SweepRunSpec spec;
  };
  std::optional<SweepPlan> plan;
  std::string plan_source;                         // where the plan came from, for errors
  std::map<std::string, std::vector<Copy>> found;  // by run name: completed copies
  std::map<std::string, std::string> unfinished;   // run name -> why its report is missing
};

// Reads every shard's sweep.json; throws when a folder is no shard or holds another sweep.
ShardContents ReadShards(const std::vector<std::string>& dirs, const SweepPlan* expected) {
  ShardContents out;
  if (expected) {
    out.plan = *expected;
    out.plan_source = "the command line";
  }
  for (const std::string& dir : dirs) {
    const std::string marker_path = dir + "/sweep.json";
    const nlohmann::json marker = ReadSweepJson(marker_path);
    if (!marker.contains("plan") || !marker.contains("runs") || !marker.contains("shard")) {
      throw InputError(marker_path, "not a sweep marker (needs plan, shard and runs)");
    }
    const SweepPlan dir_plan = SweepPlan::FromJson(marker.at("plan"), marker_path);
    if (!out.plan) {
      out.plan = dir_plan;
      out.plan_source = marker_path;
    } else if (Identity(dir_plan) != Identity(*out.plan)) {
      throw InputError(marker_path,
                       "its sweep differs from the one in " + out.plan_source + " at " +
                           JsonFirstDifference(Identity(dir_plan), Identity(*out.plan)) +
                           " (shards of one sweep must be run with the same scene, --set, --seeds and bench flags)");
    }
    const std::string shard =
        std::to_string(marker["shard"].value("index", 0)) + "/" + std::to_string(marker["shard"].value("count", 1));
    for (const nlohmann::json& r : marker.at("runs")) {
      const SweepRunSpec spec = SweepRunSpec::FromJson(r);
      const std::string run_dir = dir + "/runs/" + spec.FolderName();
      std::error_code ec;
      if (fs::exists(run_dir + "/sweep_run.json", ec) && fs::exists(run_dir + "/report.json", ec)) {
        out.found[spec.Name()].push_back({dir, spec});
      } else {
        out.unfinished[spec.Name()] = "shard " + shard + " in " + dir + " has no finished report in " + run_dir +
                                      (marker.value("finished", false) ? "" : "; that shard did not finish");
      }
    }
  }
  return out;
}

// Throws, listing every problem, unless each run of the plan was finished exactly once and no
// other run is there.
void CheckComplete(const ShardContents& shards) {
  std::vector<Problem> problems;
  std::set<std::string> expected_names;
  for (const SweepRunSpec& run : shards.plan->Runs()) {
    expected_names.insert(run.Name());
    const auto it = shards.found.find(run.Name());
    if (it == shards.found.end()) {
      const auto why = shards.unfinished.find(run.Name());
      problems.push_back(
          {"--merge", "missing run " + run.Name() +
                          (why != shards.unfinished.end() ? " (" + why->second + ")" : " (in no shard's run list)")});
    } else if (it->second.size() > 1) {
      std::string where;
      for (const ShardContents::Copy& f : it->second) where += (where.empty() ? "" : ", ") + f.dir;
      problems.push_back({"--merge", "run " + run.Name() + " appears " + std::to_string(it->second.size()) +
                                         " times (in " + where + ")"});
    }
  }
  for (const auto& [name, copies] : shards.found) {
    if (!expected_names.count(name)) {
      problems.push_back({"--merge", "run " + name + " in " + copies.front().dir + " is not part of the sweep"});
    }
  }
  if (!problems.empty()) throw InputError(problems);
}

}  // namespace

SweepSummary MergeSweep(const std::vector<std::string>& dirs, const SweepPlan* expected) {
  if (dirs.empty()) throw InputError("--merge", "no sweep output folders given");
  const ShardContents shards = ReadShards(dirs, expected);
  CheckComplete(shards);
  const SweepPlan& plan = *shards.plan;

  const std::vector<std::string> methods = plan.bench.at("methods").get<std::vector<std::string>>();
  const std::vector<SweepMetric>& metrics = SweepMetrics();
  // values[combination name][method][metric] over seeds
  std::map<std::string, std::vector<std::vector<std::vector<double>>>> values;
  std::map<std::string, std::vector<int>> seeds;
  std::vector<std::string> runs_without_queries;
  for (const auto& [name, copies] : shards.found) {
    const ShardContents::Copy& f = copies.front();
    const std::string path = f.dir + "/runs/" + f.spec.FolderName() + "/report.json";
    const nlohmann::json report = ReadSweepJson(path);
    const std::string combo = SweepSettingsName(f.spec.settings);
    auto& v = values[combo];
    v.resize(methods.size(), std::vector<std::vector<double>>(metrics.size()));
    seeds[combo].push_back(f.spec.seed);
    for (size_t m = 0; m < methods.size(); ++m) {
      if (!report.contains("methods") || !report["methods"].contains(methods[m])) {
        throw InputError(path, "has no results of method " + methods[m]);
      }
      for (size_t k = 0; k < metrics.size(); ++k)
        v[m][k].push_back(JsonNumberOrNan(report["methods"][methods[m]], metrics[k].key));
    }
    // Every method is scored on the same queries: those with a true match in their database.
    if (!methods.empty() && JsonNumberOrNan(report["methods"][methods.front()], "queries_scored") == 0) {
      runs_without_queries.push_back(name);
    }
  }

  SweepSummary summary;
  summary.plan = plan;
  summary.runs_without_queries = runs_without_queries;
  for (const Settings& s : plan.Combinations()) {
    const std::string combo = SweepSettingsName(s);
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

std::string SweepSummary::Warning() const {
  if (runs_without_queries.empty()) return "";
  std::string names;
  for (const std::string& run : runs_without_queries) names += (names.empty() ? "" : ", ") + run;
  return std::to_string(runs_without_queries.size()) + " of " + std::to_string(plan.Runs().size()) +
         " runs scored no query (no query had a true match in its database), so their metrics are \"-\": " + names +
         ". Under the laps protocol a run must last longer than its first lap: set more frames (--set frames=N) "
         "or another --protocol";
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
      out << "," << CsvNumber(s.mean, 6) << "," << CsvNumber(s.std, 6) << "," << CsvNumber(s.min, 6) << ","
          << CsvNumber(s.max, 6);
    }
    out << "\n";
  }
  return out.str();
}

std::string SweepSummary::ToMarkdown() const {
  const std::vector<SweepMetric>& metrics = SweepMetrics();
  std::ostringstream out;
  out << "# hoilcd sweep of " << plan.scene_name << "\n\n"
      << "Scene `" << SafeText(plan.scene_path) << "` (hash `" << plan.scene_hash << "`), seeds 1.." << plan.seeds
      << ", methods " << plan.bench.at("methods").dump() << ", protocol `" << plan.bench.value("protocol", "")
      << "`. Each cell: mean ± sample std [min, max] over the seeds. Every run's report is in runs/.\n\n";
  if (const std::string warning = Warning(); !warning.empty()) out << "**Warning:** " << SafeText(warning) << ".\n\n";
  out << "|";
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
      out << " " << Fixed(s.mean, d) << " ± " << Fixed(s.std, d) << " [" << Fixed(s.min, d) << ", " << Fixed(s.max, d)
          << "] |";
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

nlohmann::json SweepSummary::ToJson() const {
  nlohmann::json rows_json = nlohmann::json::array();
  for (const SweepSummaryRow& row : rows) {
    nlohmann::json settings = nlohmann::json::object(), stats = nlohmann::json::object();
    for (const auto& [key, value] : row.settings) settings[key] = value;
    for (size_t k = 0; k < row.stats.size() && k < SweepMetrics().size(); ++k) {
      const SweepStats& s = row.stats[k];
      stats[SweepMetrics()[k].key] = {{"count", s.count},
                                      {"mean", JsonNumber(s.mean)},
                                      {"std", JsonNumber(s.std)},
                                      {"min", JsonNumber(s.min)},
                                      {"max", JsonNumber(s.max)}};
    }
    rows_json.push_back({{"settings", settings}, {"method", row.method}, {"seeds", row.seeds}, {"stats", stats}});
  }
  return {{"plan", plan.ToJson()}, {"rows", rows_json}, {"runs_without_queries", runs_without_queries}};
}

void CheckSweepSummaryFolder(const std::string& out_dir) {
  std::error_code ec;
  if (!fs::exists(out_dir, ec)) return;
  if (!fs::is_directory(out_dir, ec)) throw InputError(out_dir, "is a file: expected a folder for the sweep's summary");
  // Ours: a folder a sweep ran in, or one an earlier summary went to.
  for (const OutputMarker& marker : {OutputMarker{"sweep.json", {"plan", "shard", "runs"}, "sweep"},
                                     OutputMarker{"summary.json", {"plan", "rows"}, "sweep summary"}}) {
    if (IsEarlierOutput(out_dir, marker)) return;
  }
  std::vector<std::string> taken;
  for (const std::string& name : ListFolder(out_dir)) {  // refused by name when it cannot be listed
    if (name == "summary.csv" || name == "summary.md" || name == "summary.json" ||
        (name.rfind("plot_", 0) == 0 && fs::path(name).extension() == ".png")) {
      taken.push_back(name);
    }
  }
  if (!taken.empty()) {
    throw InputError(out_dir, "holds " + JoinFileList(taken) +
                                  ", which the sweep's summary would overwrite, and no earlier hoilcd sweep "
                                  "(sweep.json or summary.json); refusing: choose another folder");
  }
}

void WriteSweepSummary(const SweepSummary& summary, const std::string& out_dir) {
  CheckSweepSummaryFolder(out_dir);
  const FolderLock lock(out_dir, FolderLock::IfBusy::kRefuse);  // held already by `hoilcd sweep`'s thread
  WriteFileAtomic(out_dir + "/summary.json", summary.ToJson().dump(2) + "\n");
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
    for (const std::string& v : axis.values) numeric = numeric && ParseJsonOrDiscarded(v).is_number();
    std::vector<double> x_of(axis.values.size());
    std::string x_label = axis.key;
    for (size_t i = 0; i < axis.values.size(); ++i) {
      x_of[i] = numeric ? ParseJsonOrDiscarded(axis.values[i]).get<double>() : static_cast<double>(i);
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
          if (b != a && axes[b].values.size() > 1)
            others += (others.empty() ? "" : ",") + row.settings[b].first + "=" + row.settings[b].second;
        }
        const std::string label = row.method + (others.empty() ? "" : " " + others);
        if (!series_by_label.count(label)) order.push_back(label);
        Series& s = series_by_label[label];
        s.label = label;
        const size_t vi = static_cast<size_t>(
            std::find(axis.values.begin(), axis.values.end(), row.settings[a].second) - axis.values.begin());
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
      const std::string name = "plot_" + SweepSafeName(axis.key) + "_" + metrics[k].key + ".png";
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
