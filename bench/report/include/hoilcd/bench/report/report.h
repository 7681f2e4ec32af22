// The benchmark report folder (SPEC.md "Evaluation protocol"): report.json with every number,
// queries.csv, report.md shaped like the paper's Table 1, and PNG figures (PR curves, the
// trajectory coloured by top-1 correctness, MRR per lap, match pictures like figures 6–7); and
// the smaller folder of one method scored outside hoilcd (hoilcd evaluate).
#pragma once

#include <functional>
#include <string>

#include "hoilcd/bench/evaluation/evaluate.h"
#include "hoilcd/bench/runner/runner.h"
#include "hoilcd/core/dataset/dataset.h"

namespace hoilcd {

struct ReportTiming {
  double render_s = 0;                     // rendering time of this run (0 when the dataset was cached)
  bool render_cached = false;              // the dataset was reused
  double bench_s = 0;                      // RunBench wall time
  double calibration_s = 0;                // render + bench of the SLAM calibration sequence (0: none)
  bool calibration_render_cached = false;  // its dataset was reused
  bool calibration_bench_cached = false;   // its thresholds were reused (calibration.json)
};

// The terminal table: method, MRR, R@1, R@5, PR-AUC, R@100%P, ms/query.
std::string FormatResultTable(const BenchResult& result);

// InputError unless `dir` may hold a report: new, empty or an earlier report (its report.json
// with hoilcd's keys); the guard of output_folder.h. Every writer below checks it first.
void CheckReportFolder(const std::string& dir);

// report.json's results: protocol, methods (metrics, intervals, options), bootstrap, strata,
// recording_runs (a dataset of 2+ runs), comparisons, the other ground truth and label_agreement.
// WriteReport adds the dataset, inspect, tracking, SLAM, timing and the diagnosis; Python's
// hoilcd.bench without a folder returns this.
nlohmann::json ResultsJson(const BenchResult& result, const BenchOptions& options);

// Writes the report folder (created if missing; files written atomically).
void WriteReport(const BenchResult& result, const Dataset& dataset, const BenchOptions& options,
                 const ReportTiming& timing, const std::string& dir);

// RunBench, then WriteReport with *timing (its bench_s set from the result), with the report's
// dataset checks run beside the bench. A report folder that cannot be used, or a protocol the
// dataset cannot take (CheckProtocolFits), fails before the bench. `before_slam`, if given, runs
// once the methods are scored and before the SLAM step, and may change its options and *timing
// (hoilcd run waits there for its calibration's thresholds).
BenchResult BenchAndWriteReport(const Dataset& dataset, BenchOptions options, ReportTiming* timing,
                                const std::string& dir, const std::function<void(SlamRunOptions*)>& before_slam = {});

// One method scored outside hoilcd (hoilcd evaluate, hoilcd.evaluate): Evaluate (evaluate.h), and
// its report folder in `dir`, checked before the work: report.json (EvaluateReportJson, the
// method described by `description`), queries.csv, report.md with the bench's results tables and
// scoring notes, and the figures of its metrics (pr_curves.png, mrr_per_lap.png).
MethodReport EvaluateAndWriteReport(const Dataset& dataset, const Labelling& labelling, const ScoreMatrix& scores,
                                    const std::string& name, const std::string& description, const std::string& dir);

}  // namespace hoilcd
