// Metrics per recording run (runs.h): when a dataset holds the same place recorded at several times
// of day, each run's queries are also scored on their own, so a report shows how every method fares
// on a later run's heat, light and occupants. Each run's MRR and R@1 carry the interval of the
// headline's block bootstrap (bootstrap.h, the same plan), resampling that run's queries.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hoilcd/bench/evaluation/bootstrap.h"
#include "hoilcd/bench/evaluation/metrics.h"
#include "hoilcd/core/dataset/runs.h"

namespace hoilcd {

struct RunMetrics {
  int run = 0;             // index in runs.json
  RunRecord record;        // as runs.json states it
  int queries = 0;         // queries whose frame lies in the run
  int queries_scored = 0;  // of them, those with a true match in their database
  std::vector<std::string> methods;
  std::vector<double> mrr, recall_at_1;                      // per method, parallel to methods
  std::vector<Interval> mrr_interval, recall_at_1_interval;  // per method
};

// One row per run, in run order; none for a dataset of one run (its report has no per-run block).
// `records`: each method's MethodMetrics::queries, the same queries in query order. `threads`: 0 =
// every CPU; the intervals do not depend on it.
std::vector<RunMetrics> MetricsPerRun(const std::vector<RunRecord>& runs, const std::vector<std::string>& names,
                                      const std::vector<const std::vector<QueryRecord>*>& records,
                                      const BootstrapPlan& plan, uint64_t seed, int threads = 0);

// report.json's "recording_runs": [{"run", "time_of_day_h", "day", "start_time_s", "first_frame",
// "frames", "queries", "queries_scored", "methods": {name: {"mrr", "recall_at_1", "intervals":
// {"mrr": [low, high], "recall_at_1": [low, high]}}}}, ...]; null for a figure without queries.
nlohmann::json MetricsPerRunJson(const std::vector<RunMetrics>& rows);

// When a run was recorded, for people: "day 1, 13:30" (the time left out when runs.json does not
// state it).
std::string WhenRecorded(const RunRecord& run);

// report.md's "Results by recording run" section; "" without rows.
std::string MetricsPerRunMarkdown(const std::vector<RunMetrics>& rows, double confidence);

}  // namespace hoilcd
