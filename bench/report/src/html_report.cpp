#include "hoilcd/bench/report/html_report.h"

#include "hoilcd/bench/methods/methods.h"
#include "hoilcd/bench/report/gallery.h"
#include "hoilcd/bench/report/gallery_sample.h"
#include "hoilcd/bench/report/html.h"
#include "hoilcd/core/util/file_io.h"
#include "hoilcd/core/util/text.h"

namespace hoilcd {
namespace {

// The headline metrics with their intervals, one sortable row per method.
std::string ResultsSection(const std::vector<MethodRun>& runs, const BootstrapPlan& plan) {
  std::vector<std::vector<HtmlCell>> rows;
  const bool intervals = plan.resamples > 0;
  for (const MethodRun& run : runs) {
    const MethodMetrics& m = run.metrics;
    const HeadlineIntervals& i = run.intervals;
    const auto cell = [&](double v, const Interval& in) { return intervals ? IntervalCell(v, in) : NumberCell(v); };
    rows.push_back({TextCell(run.name), cell(m.mrr, i.mrr), cell(m.recall_at_1, i.recall_at_1),
                    cell(m.recall_at_5, i.recall_at_5), cell(m.recall_at_10, i.recall_at_10), cell(m.pr_auc, i.pr_auc),
                    cell(m.recall_at_100p, i.recall_at_100p), NumberCell(m.ms_per_query, 2)});
  }
  std::string html = "<h2>Results</h2>\n";
  if (intervals) {
    html += "<p class=\"note\">In brackets: " + Fixed(100 * plan.confidence, 0) +
            " % intervals, a circular block "
            "bootstrap of the queries in time order (" +
            std::to_string(plan.resamples) + " resamples, blocks of " + std::to_string(plan.block_queries) +
            " queries). Click a header to sort.</p>\n";
  }
  if (!runs.empty()) {
    const MethodMetrics& m = runs.front().metrics;
    html += "<p>" + std::to_string(m.queries_scored) + " queries scored, " + std::to_string(m.queries_skipped) +
            " skipped (no true match in their database).</p>\n";
  }
  return html + SortableTable({"method", "MRR", "R@1", "R@5", "R@10", "PR-AUC", "R@100%P", "ms/query"}, rows);
}

// Every pair of methods on MRR, the better first, separated pairs first; folded, as there are
// n(n-1)/2 of them.
std::string ComparisonsSection(const std::vector<PairedComparison>& comparisons) {
  std::vector<std::vector<HtmlCell>> rows;
  int separated = 0;
  for (bool want_separated : {true, false}) {
    for (const PairedComparison& c : comparisons) {
      if (c.queries <= 0 || c.Separated() != want_separated) continue;
      separated += want_separated ? 1 : 0;
      rows.push_back({TextCell(c.a + " > " + c.b), IntervalCell(c.delta, c.interval), NumberCell(c.queries, 0),
                      TextCell(want_separated ? "yes" : "no")});
    }
  }
  if (rows.empty()) return "";
  return "<h3>Paired comparisons (MRR)</h3>\n<details><summary>" + std::to_string(rows.size()) + " pairs, " +
         std::to_string(separated) +
         " separated (their interval excludes 0)</summary>\n<p class=\"note\">The "
         "difference of per-query reciprocal ranks over the queries both methods scored, with its interval from "
         "the same resampled blocks. Where the interval holds 0, this sequence cannot tell the two apart.</p>\n" +
         SortableTable({"pair (better first)", "MRR difference", "queries", "separated"}, rows) + "</details>\n";
}

std::string StrataSection(const std::vector<StratumRow>& strata) {
  if (strata.empty()) return "";
  std::vector<std::string> headers = {"stratum", "queries", "chance MRR"};
  for (const std::string& m : strata.front().methods) headers.push_back(m);
  std::vector<std::vector<HtmlCell>> rows;
  for (const StratumRow& row : strata) {
    std::vector<HtmlCell> cells = {TextCell(row.stratification + ": " + row.stratum), NumberCell(row.queries, 0),
                                   NumberCell(row.chance_mrr)};
    for (size_t m = 0; m < row.methods.size(); ++m) {
      cells.push_back({Fixed(row.mrr[m]) + " / " + Fixed(row.recall_at_1[m]), row.mrr[m]});
    }
    rows.push_back(std::move(cells));
  }
  return "<h3>Results by condition</h3>\n<p class=\"note\">Each method's MRR / R@1 on the scored queries of each "
         "stratum "
         "(definitions in docs/guide/protocol.md); chance is the MRR of a random order.</p>\n" +
         SortableTable(headers, rows);
}

std::string RecordingRunsSection(const std::vector<RunMetrics>& per_run) {
  if (per_run.empty()) return "";
  std::vector<std::string> headers = {"recording run", "queries scored"};
  for (const std::string& m : per_run.front().methods) headers.push_back(m + " MRR");
  std::vector<std::vector<HtmlCell>> rows;
  for (const RunMetrics& r : per_run) {
    std::vector<HtmlCell> cells = {NumberCell(r.run, 0), NumberCell(r.queries_scored, 0)};
    for (size_t m = 0; m < r.methods.size(); ++m) cells.push_back(IntervalCell(r.mrr[m], r.mrr_interval[m]));
    rows.push_back(std::move(cells));
  }
  return "<h3>By recording run</h3>\n" + SortableTable(headers, rows);
}

std::string OtherGroundTruthSection(const BenchResult& result) {
  std::vector<std::vector<HtmlCell>> rows;
  for (const MethodRun& run : result.runs) {
    const MethodMetrics& m = run.other_metrics;
    rows.push_back({TextCell(run.name), NumberCell(m.mrr), NumberCell(m.recall_at_1), NumberCell(m.recall_at_5),
                    NumberCell(m.pr_auc), NumberCell(run.metrics.mrr)});
  }
  const LabelDisagreement& labels = result.label_disagreement;
  return "<h3>The same scores under " + EscapeHtml(result.other_ground_truth) + " ground truth</h3>\n<p>" +
         std::to_string(labels.queries_differing) + " of " + std::to_string(labels.queries) +
         " queries have a different set of true matches.</p>\n" +
         SortableTable({"method", "MRR", "R@1", "R@5", "PR-AUC", "MRR (" + result.ground_truth + ")"}, rows);
}

std::string SlamSection(const SlamResult& slam, const std::vector<PoseRecord>& poses) {
  const auto row = [](const std::string& name, const SlamScore& s, double threshold) {
    return std::vector<HtmlCell>{TextCell(name),
                                 NumberCell(s.ate_rmse_m),
                                 NumberCell(s.rpe_rmse_m),
                                 NumberCell(s.loops_accepted, 0),
                                 NumberCell(s.false_loops, 0),
                                 NumberCell(threshold, 2)};
  };
  std::vector<std::vector<HtmlCell>> rows = {row("odometry alone", slam.odometry, NAN)};
  for (const SlamScore& s : slam.oracle)
    if (s.backend == slam.backend) rows.push_back(row("oracle loops", s, NAN));
  for (const MethodSlam& m : slam.methods) rows.push_back(row(m.method, m.Headline(slam.backend), m.threshold));
  std::string html =
      "<h2>SLAM</h2>\n<p class=\"note\">Each method's accepted loops in an SE(2) pose graph with the "
      "wheel odometry (back end " +
      EscapeHtml(slam.backend) + "); ATE and RPE against the true poses.</p>\n" +
      SortableTable({"trajectory", "ATE RMSE (m)", "RPE RMSE (m)", "loops", "false loops", "threshold"}, rows);
  for (const std::string& note : slam.notes) html += "<p class=\"note\">" + EscapeHtml(note) + "</p>\n";
  return html + SlamTrajectorySvg(slam, poses);
}

// The report's PNG figures, each embedded (the page needs no other file).
std::string FiguresSection(const HtmlReportInput& input) {
  if (input.figures.empty()) return "";
  std::string html = "<h2>Figures</h2>\n";
  for (const std::string& f : input.figures) {
    html += "<div class=\"figure\"><h4>" + EscapeHtml(f) + "</h4><img alt=\"" + EscapeHtml(f) + "\" src=\"" +
            DataUri("image/png", ReadFileBytes(input.dir + "/" + f)) + "\"></div>\n";
  }
  return html;
}

std::string Links() {
  return "<p class=\"note\">The same report as text: <a href=\"report.md\">report.md</a>, every number in "
         "<a href=\"report.json\">report.json</a>, one row per method and query in <a href=\"queries.csv\">"
         "queries.csv</a>. Jump to the <a href=\"#gallery-section\">gallery of queries</a>.</p>\n";
}

std::string DatasetLine(const Dataset& dataset, const ProtocolOptions& protocol) {
  return "<p>Dataset <code>" + EscapeHtml(dataset.dir()) + "</code> (" + std::to_string(dataset.num_frames()) +
         " frames, seed " + std::to_string(dataset.manifest().seed) + "), protocol <code>" +
         EscapeHtml(protocol.protocol) + "</code>, " + EscapeHtml(protocol.ground_truth) +
         " ground truth, exclusion window " + Fixed(protocol.exclusion_window_s, 1) + " s.</p>\n";
}

}  // namespace

HtmlReport BenchReportHtml(const BenchResult& result, const Dataset& dataset, const BenchOptions& options,
                           const HtmlReportInput& input) {
  GalleryInput gallery_input{dataset, result.queries,   result.conditions, StratificationsOf(result.strata),
                             {},      &result.features, options.params,    input.gallery};
  for (const MethodRun& run : result.runs) gallery_input.methods.push_back({run.name, &run.metrics.queries});
  const Gallery gallery = MakeGallery(gallery_input);
  std::string body = "<h1>hoilcd loop-closure report</h1>\n" + DatasetLine(dataset, options.protocol) + Links() +
                     ResultsSection(result.runs, result.bootstrap) + ComparisonsSection(result.comparisons) +
                     StrataSection(result.strata) + RecordingRunsSection(result.per_run) +
                     OtherGroundTruthSection(result);
  if (result.slam_evaluated) body += SlamSection(result.slam, dataset.poses());
  body += gallery.html + FiguresSection(input);
  body += "<h2>Methods</h2>\n<ul>";
  for (const MethodRun& run : result.runs) {
    body +=
        "<li><code>" + EscapeHtml(run.name) + "</code>: " + EscapeHtml(FindMethod(run.name).Description()) + "</li>";
  }
  body += "</ul>\n";
  return {HtmlPage("hoilcd report: " + dataset.dir(), body), gallery.sampled};
}

std::string OnlineReportHtml(const OnlineResult& result, const Dataset& dataset) {
  std::vector<std::vector<HtmlCell>> rows;
  for (const OnlineMethodRun& run : result.runs) {
    const MethodMetrics& m = run.metrics;
    const HeadlineIntervals& i = run.intervals;
    rows.push_back({TextCell(run.name), IntervalCell(m.mrr, i.mrr), IntervalCell(m.recall_at_1, i.recall_at_1),
                    IntervalCell(m.recall_at_5, i.recall_at_5), NumberCell(run.p50_ms, 2), NumberCell(run.p99_ms, 2)});
  }
  const std::string body = "<h1>hoilcd online loop-closure report</h1>\n<p>Dataset <code>" + EscapeHtml(dataset.dir()) +
                           "</code> (" + std::to_string(result.frames) + " frames), protocol <code>" +
                           EscapeHtml(result.protocol) + "</code>, " + EscapeHtml(result.ground_truth) +
                           " ground truth. The same report as text: <a href=\"report.md\">report.md</a>, "
                           "<a href=\"report.json\">report.json</a>.</p>\n<p>" +
                           std::to_string(result.queries_processed) + " queries processed, " +
                           std::to_string(result.queries_scored) + " scored; the shortlist held a true match for " +
                           std::to_string(result.shortlist_hits) + " of them (recall " +
                           Fixed(result.shortlist_recall) + ").</p>\n" +
                           SortableTable({"method", "MRR", "R@1", "R@5", "ms/query p50", "ms/query p99"}, rows) +
                           RecordingRunsSection(result.per_run);
  return HtmlPage("hoilcd online report: " + dataset.dir(), body);
}

HtmlReport EvaluateReportHtml(const MethodRun& run, const BootstrapPlan& plan, const std::vector<Query>& queries,
                              const std::vector<QueryConditions>& conditions, const std::vector<StratumRow>& strata,
                              const Dataset& dataset, const ProtocolOptions& protocol, const std::string& description,
                              const HtmlReportInput& input) {
  GalleryInput gallery_input{
      dataset, queries, conditions,   StratificationsOf(strata), {{run.name, &run.metrics.queries}},
      nullptr, {},      input.gallery};
  const Gallery gallery = MakeGallery(gallery_input);
  const std::string body = "<h1>hoilcd evaluate: " + EscapeHtml(run.name) + "</h1>\n<p>" + EscapeHtml(description) +
                           "</p>\n" + DatasetLine(dataset, protocol) + Links() + ResultsSection({run}, plan) +
                           StrataSection(strata) + gallery.html + FiguresSection(input);
  return {HtmlPage("hoilcd evaluate: " + run.name, body), gallery.sampled};
}

}  // namespace hoilcd
