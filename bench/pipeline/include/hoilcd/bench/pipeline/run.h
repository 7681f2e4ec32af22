// `hoilcd run`: render a scene (reusing a cached dataset whose manifest matches the scene's
// hash), benchmark it, write the report, and say how long each part took.
#pragma once

#include <atomic>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hoilcd/bench/report/report.h"
#include "hoilcd/bench/runner/runner.h"
#include "hoilcd/core/util/option_table.h"
#include "hoilcd/sim/scene/scene.h"

namespace hoilcd {

// Defaults and ranges: Table() in run.cpp.
struct RunOptions {
  std::string cache_dir;   // datasets and reports go to CACHE/<scene>-<hash>/
  std::string report_dir;  // default CACHE/<scene>-<hash>/report
  int threads;             // 0 = every core
  bool keep_datasets;      // false: each dataset (and its SLAM calibration's) is deleted once its report is written
  const std::atomic<bool>* cancel = nullptr;  // set by code to stop early; a hook, not in the table
  // SLAM loop thresholds (when bench.slam and no --loop-threshold): each method's 100 %-precision
  // threshold on the scene rendered with seed + calibration_seed_offset. Its dataset is cached
  // like any run's and its thresholds in calibration.json beside it, keyed by that dataset's
  // manifest, the hoilcd program's own bytes and the bench options a user can set.
  uint64_t calibration_seed_offset;

  RunOptions();  // the registered defaults
  // Every field once: name, default, unit, range, description.
  static const OptionTable<RunOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

struct RunOutcome {
  std::string dataset_dir;
  std::string report_dir;
  BenchResult result;
  ReportTiming timing;
  std::vector<std::string> warnings;  // the render's and the dataset's, for the caller to print
  std::string calibration_dir;        // dataset the loop thresholds came from (empty: none)
};

// The folder a scene's dataset is cached in: CACHE/<name>-<first 12 hex of the hash>.
std::string RunFolder(const Scene& scene, const std::string& cache_dir);

// The bench settings a user can set that change a report (methods, protocol, keypoint detector,
// --param, strata, SLAM and its back end and loop threshold), as JSON: what a sweep plan and a
// suite's identity record, what decides whether a rerun keeps a run's report, and what keys the
// SLAM calibration's cache.
nlohmann::json BenchSettingsJson(const BenchOptions& options);

RunOutcome RunScene(const Scene& scene, const BenchOptions& bench, const RunOptions& options);

// A run of a sweep or suite, kept in its report folder `dir` beside a record file: the record
// (the run, its scene hash, the bench settings) says what made the report there.
struct RecordedRun {
  std::string dir;          // the report folder
  std::string record_file;  // e.g. "sweep_run.json", beside report.json
  nlohmann::json record;

  // Whether an earlier run left exactly this record beside a report.json (an unreadable record
  // is not a match: the run is done again).
  bool Kept() const;
  // RunScene with its report in dir, then the record written; the old record is removed first,
  // so an interrupted run never leaves a record beside a partial report.
  void Run(const Scene& scene, const BenchOptions& bench, RunOptions options) const;
};

}  // namespace hoilcd
