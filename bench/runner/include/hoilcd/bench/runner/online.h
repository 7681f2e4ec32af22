// Online loop closure, as a robot runs it (`hoilcd bench --online`): frames come in time order, a
// frame joins the database once it is older than the exclusion window, and each query first takes a
// shortlist of K frames from a FAISS index of global descriptors (the thumbnails, shortlist_index.h),
// then every method scores only those K (the point-set methods' RANSAC, fusion's ranks). A frame
// the shortlist left out is unranked: it ties below every shortlisted one (metrics.h ShortlistRecord).
// Queries are the protocol's (laps: the later laps; revisit: every frame; runs: the later recording
// runs); the database is every older frame, in all. Reported per method: the metrics with their
// intervals (and per recording run), the shortlist's recall, and ms per query at p50 and p99 as the
// database grows (bench/report's online_report.h writes them). The offline runner (runner.h) is
// unchanged.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hoilcd/bench/evaluation/bootstrap.h"
#include "hoilcd/bench/evaluation/metrics.h"
#include "hoilcd/bench/evaluation/run_metrics.h"
#include "hoilcd/bench/methods/bench_options.h"
#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/place_recognition/shortlist_index.h"

namespace hoilcd {

// Time per query of queries whose database size lies in [database_from, database_to). Every
// percentile here is stats.h's Quantile: NaN (null in JSON, "–" in report.md) over no values.
struct OnlineTimingRow {
  int64_t database_from = 0;
  int64_t database_to = 0;
  int queries = 0;
  double p50_ms = 0;
  double p99_ms = 0;
};

struct OnlineMethodRun {
  std::string name;
  MethodMetrics metrics;         // records from ShortlistRecord; no timing (query_ms has it)
  HeadlineIntervals intervals;   // OnlineResult::bootstrap says how
  std::vector<double> query_ms;  // per processed query: shortlist search + the method's scoring of it
  double p50_ms = 0, p99_ms = 0;
  std::vector<OnlineTimingRow> by_database_size;
  nlohmann::json options;  // the method's own options as it ran; null: none
};

struct OnlineResult {
  ShortlistOptions shortlist;
  std::string protocol;      // which frames were queries
  std::string ground_truth;  // odometry or true
  int frames = 0;
  int queries_processed = 0;      // queries with a non-empty database (each searched and scored)
  int queries_scored = 0;         // of those, with a true match in the database
  int shortlist_hits = 0;         // scored queries with a true match in their shortlist
  double shortlist_recall = 0;    // shortlist_hits / queries_scored
  std::vector<double> search_ms;  // per processed query: the shortlist search alone
  std::vector<OnlineTimingRow> search_by_database_size;
  double insert_p50_ms = 0, insert_p99_ms = 0;  // adding one frame to the shortlist index (NaN: none added)
  double index_bytes = 0;                       // the shortlist index at the end (ShortlistIndex::MemoryBytes)
  double peak_rss_bytes = 0;                    // this process's peak resident memory when done
  std::vector<OnlineMethodRun> runs;            // in the order asked for
  std::vector<std::string> skipped;             // optional methods left out, each "<method>: <why>"
  BootstrapPlan bootstrap;
  std::vector<RunMetrics> per_run;  // per recording run of the dataset (none for one run)
  double seconds = 0;               // wall time, front ends included
  const OnlineMethodRun* Find(const std::string& name) const;
};

// Methods must be Online() (point-set methods and fusion); one named that is not is an InputError
// on --methods, one brought in by "all" or "paper" is left out with a note. Default: slcd, dlcd,
// fusion. --ground-truth overlap is refused (it labels pairs from the EXRs).
OnlineResult RunOnlineBench(const Dataset& dataset, const BenchOptions& options, const ShortlistOptions& shortlist);

// Rows of timing by database size: decades split 1-2-5 (0-1000, 1000-2000, 2000-5000, ...), only
// those holding a query. database_sizes and ms are parallel.
std::vector<OnlineTimingRow> TimingByDatabaseSize(const std::vector<int64_t>& database_sizes,
                                                  const std::vector<double>& ms);

}  // namespace hoilcd
