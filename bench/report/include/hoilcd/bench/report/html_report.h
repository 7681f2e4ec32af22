// report.html, the report folder's page for a browser, written beside report.md by the bench, run
// and evaluate (and suite_report.html beside suite_report.md): one file with everything embedded
// (figures and frames as data URIs, an inline script, nothing from the network), holding the
// results with their intervals in sortable tables, the strata and paired comparisons, the SLAM
// trajectories against ground truth as inline SVG, the figures, and the gallery of queries.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "hoilcd/bench/evaluation/evaluate.h"
#include "hoilcd/bench/evaluation/suite_summary.h"
#include "hoilcd/bench/report/gallery_sample.h"
#include "hoilcd/bench/runner/online.h"
#include "hoilcd/bench/runner/runner.h"
#include "hoilcd/core/dataset/dataset.h"

namespace hoilcd {

// What a report page shows besides the result: its figures (PNG files already written in `dir`,
// in report.md's order) and how the gallery samples its queries.
struct HtmlReportInput {
  std::string dir;                   // the report folder
  std::vector<std::string> figures;  // file names in dir
  GallerySampling gallery;           // SampleGallery's
};

// The bench's page (hoilcd bench and run) and its gallery's sample (query indices), which report.json
// lists; the caller writes the page.
struct HtmlReport {
  std::string html;
  std::vector<size_t> gallery;  // sampled query indices, ascending
};
HtmlReport BenchReportHtml(const BenchResult& result, const Dataset& dataset, const BenchOptions& options,
                           const HtmlReportInput& input);

// hoilcd evaluate's page: one method scored outside hoilcd (its gallery shows frames, no features).
HtmlReport EvaluateReportHtml(const MethodRun& run, const BootstrapPlan& plan, const std::vector<Query>& queries,
                              const std::vector<QueryConditions>& conditions, const std::vector<StratumRow>& strata,
                              const Dataset& dataset, const ProtocolOptions& protocol, const std::string& description,
                              const HtmlReportInput& input);

// The online bench's page (bench --online): the shortlist's figures and each method's results with
// intervals and ms per query; no gallery (the online bench keeps no databases to draw from).
std::string OnlineReportHtml(const OnlineResult& result, const Dataset& dataset);

// The inline SVG of the SLAM trajectories: ground truth, odometry and each method's optimised path
// (headline back end), x right and y up in metres; "" when SLAM did not run.
std::string SlamTrajectorySvg(const SlamResult& slam, const std::vector<PoseRecord>& poses);

// suite_report.html: the summary's tables, and one row per run linking to its report.html
// (`run_reports`: run -> its report folder, relative to the suite report's).
std::string SuiteReportHtml(const SuiteSummary& summary, const std::map<std::string, std::string>& run_reports);

}  // namespace hoilcd
