// The summary of a sweep (sweep.h): shard outputs read back and checked to hold every run exactly
// once, each metric summarised over seeds per combination and method, written as CSV, Markdown
// and plots of each metric against each swept value.
#pragma once

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "hoilcd/bench/pipeline/sweep.h"

namespace hoilcd {

// Mean, sample standard deviation (0 for one value), minimum and maximum of the finite values.
struct SweepStats {
  int count = 0;  // finite values summarised
  double mean = NAN, std = NAN, min = NAN, max = NAN;
  static SweepStats Of(const std::vector<double>& values);
};

// A metric of the summary: its key in report.json's methods.<name> and its table label.
struct SweepMetric {
  std::string key;    // e.g. "recall_at_1"
  std::string label;  // e.g. "R@1"
};
const std::vector<SweepMetric>& SweepMetrics();  // MRR, R@1, R@5, PR-AUC, R@100%P, ms/query

// One combination of values and one method, summarised over its seeds.
struct SweepSummaryRow {
  std::vector<std::pair<std::string, std::string>> settings;  // axis order
  std::string method;
  std::vector<int> seeds;         // seeds found, ascending
  std::vector<SweepStats> stats;  // parallel to SweepMetrics()
};

struct SweepSummary {
  SweepPlan plan;
  std::vector<SweepSummaryRow> rows;              // combinations in Combinations() order, methods in plan order
  std::vector<std::string> runs_without_queries;  // runs (by name, sorted) whose report scored no query

  // "" when every run scored queries; else which runs scored none and what to do (the summary
  // shows it above the table; `hoilcd sweep` prints it on stderr).
  std::string Warning() const;
  std::string ToCsv() const;        // one row per combination and method: mean, std, min, max
  std::string ToMarkdown() const;   // the same as a table of "mean ± std [min, max]"
  std::string FormatTable() const;  // terminal: mean ± std per metric
  nlohmann::json ToJson() const;    // the plan and every row's statistics (summary.json)
};

// Reads the runs of sweep output folders (their sweep.json and each assigned run's report.json)
// and checks that together they hold every run of the plan exactly once: else InputError naming
// the missing, duplicated or unexpected runs. With `expected`, every folder's plan must equal it;
// without, the folders' plans must agree with each other.
SweepSummary MergeSweep(const std::vector<std::string>& dirs, const SweepPlan* expected = nullptr);

// Writes OUT/summary.csv, OUT/summary.md and OUT/plot_<key>_<metric>.png for every axis with at
// least two values: metric against value, one line per method (and per value of the other axes),
// the mean over seeds with a band from the minimum to the maximum.
void WriteSweepSummary(const SweepSummary& summary, const std::string& out_dir);

// The summary's folder may hold other things (the shards' folders, logs); InputError when it
// holds a file the summary would overwrite (summary.csv, .md, .json, plot_*.png) but is neither
// a sweep's folder (sweep.json) nor an earlier summary's (summary.json). WriteSweepSummary checks
// it; call it before long work too.
void CheckSweepSummaryFolder(const std::string& out_dir);

}  // namespace hoilcd
