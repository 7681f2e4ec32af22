#include "hoilcd/bench/report/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <future>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "hoilcd/bench/methods/methods.h"
#include "hoilcd/bench/report/diagnosis.h"
#include "hoilcd/bench/report/figures.h"
#include "hoilcd/bench/report/gallery_sample.h"
#include "hoilcd/bench/report/html_report.h"
#include "hoilcd/bench/report/inspect.h"
#include "hoilcd/bench/report/output_folder.h"
#include "hoilcd/bench/report/slam_report.h"
#include "hoilcd/core/util/file_io.h"
#include "hoilcd/core/util/folder_lock.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/core/util/safe_text.h"
#include "hoilcd/core/util/text.h"

namespace hoilcd {
namespace {

// Notes on the metrics of any method's scores (the bench's reports and hoilcd evaluate's)...
const char* const kScoringNotes[] = {
    "Precision-recall and R@100%P cover the scored queries, those with a true match in their "
    "database (revisits); queries without one are counted as skipped and cannot add false "
    "positives here.",
    "Ranks with tied scores are expected values over a uniformly random order of the tied group "
    "(many database frames share 0 inliers); no rank depends on database order.",
};
// ... and on the built-in methods (the bench's reports, after those).
const char* const kMethodNotes[] = {
    "SLCD uses Shi-Tomasi (GFTT) corners with SuperPoint-like settings (4 px NMS, 4 px border, up "
    "to 1000 corners): pretrained SuperPoint weights cannot be shipped. Only coordinates are used, "
    "as in the paper.",
    "ByteTrack follows the Python reference (score fusion, 0.1 low-score floor); the official C++ "
    "ports differ. Lost tracks are kept 30 frames.",
    "Fusion ranks tied scores by their average position before reciprocal rank fusion, so fused "
    "scores do not depend on database order either.",
};

// The paper's methods in one panel and the rest (variants, baselines, oracles) in another, so no
// curve hides under its variant's; both share the recall axis, fitted to the longest curve.
cv::Mat PrFigure(const std::vector<MethodRun>& runs) {
  std::vector<Series> paper, others;
  double max_recall = 0;
  for (const MethodRun& run : runs) {
    const bool from_paper = IsMethod(run.name) && FindMethod(run.name).FromPaper();
    Series s;
    s.label = run.name;
    s.colour = PaletteColour(static_cast<int>((from_paper ? paper : others).size()));
    for (const PrPoint& p : run.metrics.pr_curve) {
      s.x.push_back(p.recall);
      s.y.push_back(p.precision);
      if (std::isfinite(p.recall)) max_recall = std::max(max_recall, p.recall);
    }
    (from_paper ? paper : others).push_back(s);
  }
  PlotOptions o;
  o.x_label = "recall";
  o.y_label = "precision";
  o.x_range = std::make_pair(0.0, std::min(1.0, std::ceil(max_recall * 10 + 0.5) / 10));
  o.y_range = std::make_pair(0.0, 1.05);
  if (paper.empty() || others.empty()) {
    o.title = "Top-1 precision-recall";
    return LinePlot(paper.empty() ? others : paper, o);
  }
  o.width_px = o.width_px * 3 / 4;
  o.title = "Top-1 precision-recall: the paper's methods";
  cv::Mat left = LinePlot(paper, o), both;
  o.title = "... variants, baselines and oracles";
  cv::hconcat(left, LinePlot(others, o), both);
  return both;
}

cv::Mat LapFigure(const std::vector<MethodRun>& runs) {
  std::set<int> laps;
  for (const MethodRun& run : runs)
    for (const auto& [lap, _] : run.metrics.per_lap) laps.insert(lap);
  std::vector<std::string> groups;
  for (int lap : laps) groups.push_back("lap " + std::to_string(lap + 1));
  std::vector<Series> series;
  for (const MethodRun& run : runs) {
    Series s;
    s.label = run.name;
    for (int lap : laps) {
      const auto it = run.metrics.per_lap.find(lap);
      s.y.push_back(it == run.metrics.per_lap.end() || !std::isfinite(it->second.mrr) ? 0.0 : it->second.mrr);
    }
    series.push_back(s);
  }
  PlotOptions o;
  o.title = "MRR per lap (queries of that lap)";
  o.y_label = "MRR";
  return BarPlot(groups, series, o);
}

cv::Mat TrajectoryFigure(const BenchResult& result, const MethodRun& run, const Dataset& dataset) {
  const std::vector<PoseRecord>& poses = dataset.poses();
  std::vector<TrajectoryPoint> points;
  std::vector<TrajectoryLink> links;
  const cv::Scalar grey(170, 170, 170), green(80, 160, 40), red(40, 40, 220), database(200, 150, 90);
  std::vector<bool> is_query(poses.size(), false);
  for (const QueryRecord& q : run.metrics.queries) {
    is_query[q.frame] = true;
    const PoseRecord& p = poses[q.frame];
    const cv::Scalar c = !q.scored ? grey : (q.top1_is_true_match ? green : red);
    points.push_back({p.x_m, p.y_m, c});
    if (q.scored && !q.top1_is_true_match && q.top1_frame >= 0) {
      const PoseRecord& r = poses[q.top1_frame];
      links.push_back({cv::Point2d(p.x_m, p.y_m), cv::Point2d(r.x_m, r.y_m), red});
    }
  }
  for (size_t f = 0; f < poses.size(); ++f)
    if (!is_query[f]) points.push_back({poses[f].x_m, poses[f].y_m, database});
  (void)result;
  PlotOptions o;
  o.title = "Trajectory, top-1 of " + run.name;
  o.x_label = "x (m)";
  o.y_label = "y (m)";
  return TrajectoryPlot(points, links, dataset.footprints(),
                        {{"correct top-1", green},
                         {"wrong top-1 (line to it)", red},
                         {"no true match", grey},
                         {"database only", database}},
                        o);
}

// A row like the paper's figure 6: query with its features, the top-1, the best true match.
std::vector<MatchTile> MatchRow(const BenchResult& result, const MethodRun& run, size_t query_index,
                                const Dataset& dataset) {
  const Query& q = result.queries[query_index];
  const QueryRecord& rec = run.metrics.queries[query_index];
  const ShownFeatures shown = FindMethod(run.name).Features();
  const bool hoi = IsHoi(shown);
  auto features = [&](int frame) { return result.features[frame].Points(shown); };
  int best_true = -1;
  double best_score = -1;
  for (size_t j = 0; j < q.database.size(); ++j) {
    if (q.is_true_match[j] && run.scores[query_index][j] > best_score) {
      best_score = run.scores[query_index][j];
      best_true = q.database[j];
    }
  }
  std::vector<MatchTile> row;
  const cv::Scalar colour = hoi ? cv::Scalar(255, 255, 0) : cv::Scalar(0, 255, 0);
  row.push_back({dataset.Thermal(q.frame), "query " + std::to_string(q.frame), {}, colour});
  row.push_back({dataset.Thermal(q.frame), run.name + " features", features(q.frame), colour});
  const std::string tie = rec.top1_tie_size > 1 ? " (" + std::to_string(rec.top1_tie_size) + " tied)" : "";
  row.push_back({dataset.Thermal(rec.top1_frame),
                 "top-1 " + std::to_string(rec.top1_frame) + (rec.top1_is_true_match ? " ok" : " wrong") +
                     " s=" + Fixed(rec.top1_score, 0) + tie,
                 features(rec.top1_frame), colour});
  row.push_back(
      {best_true >= 0 ? dataset.Thermal(best_true) : cv::Mat(),
       best_true >= 0 ? "true match " + std::to_string(best_true) + " s=" + Fixed(best_score, 0) : "no true match",
       best_true >= 0 ? features(best_true) : std::vector<cv::Point2f>{}, colour});
  return row;
}

}  // namespace

std::string FormatResultTable(const BenchResult& result) {
  std::ostringstream out;
  char line[256];
  const std::string other = "MRR(" + result.other_ground_truth + ")";
  std::snprintf(line, sizeof(line), "%-11s %6s %6s %6s %7s %8s %9s %14s\n", "method", "MRR", "R@1", "R@5", "PR-AUC",
                "R@100%P", "ms/query", other.c_str());
  out << "ground truth: "
      << (result.ground_truth == "overlap" ? "overlap (the view two frames share)" : result.ground_truth + " positions")
      << " (columns before the last)\n"
      << line;
  for (const MethodRun& run : result.runs) {
    const MethodMetrics& m = run.metrics;
    std::snprintf(line, sizeof(line), "%-11s %6s %6s %6s %7s %8s %9s %14s\n", run.name.c_str(), Fixed(m.mrr).c_str(),
                  Fixed(m.recall_at_1).c_str(), Fixed(m.recall_at_5).c_str(), Fixed(m.pr_auc).c_str(),
                  Fixed(m.recall_at_100p).c_str(), Fixed(m.ms_per_query, 2).c_str(),
                  Fixed(run.other_metrics.mrr).c_str());
    out << line;
  }
  if (!result.runs.empty()) {
    const MethodMetrics& m = result.runs.front().metrics;
    out << m.queries_scored << " queries scored, " << m.queries_skipped
        << " skipped (no true match in their database); " << result.label_disagreement.queries_differing << " of "
        << result.label_disagreement.queries << " queries have other true matches under " << result.other_ground_truth
        << " labels\n";
  }
  return out.str();
}

nlohmann::json ResultsJson(const BenchResult& result, const BenchOptions& options) {
  const LabelDisagreement& labels = result.label_disagreement;
  nlohmann::json report;
  report["protocol"] = ProtocolOptions::Table().ToJson(options.protocol);
  for (const MethodRun& run : result.runs) {
    nlohmann::json m = run.metrics.ToJson();
    m["description"] = FindMethod(run.name).Description();
    if (!run.options.is_null()) m["options"] = run.options;  // as it ran, --param values included
    m["intervals"] = run.intervals.ToJson();
    report["methods"][run.name] = m;
  }
  report["bootstrap"] = result.bootstrap.ToJson();
  report["strata"] = StrataJson(result.strata);
  if (!result.per_run.empty()) report["recording_runs"] = MetricsPerRunJson(result.per_run);
  report["conditions"] = {{"blank_spread_k", kBlankSpreadK},
                          {"contrast_k", kContrastK},
                          {"per_query", "queries.csv, one row per method and query"}};
  for (const PairedComparison& c : result.comparisons) report["comparisons"].push_back(c.ToJson());
  report["other_ground_truth"] = {{"ground_truth", result.other_ground_truth},
                                  {"queries_differing", labels.queries_differing},
                                  {"queries", labels.queries},
                                  {"pairs_differing", labels.pairs_differing},
                                  {"queries_with_match_only_under_chosen", labels.scored_only_in_a},
                                  {"queries_with_match_only_under_other", labels.scored_only_in_b},
                                  {"methods", nlohmann::json::object()}};
  for (const MethodRun& run : result.runs)
    report["other_ground_truth"]["methods"][run.name] = run.other_metrics.ToJson();
  report["label_agreement"] = nlohmann::json::array();
  for (const LabelAgreement& g : result.label_agreements) report["label_agreement"].push_back(g.ToJson());
  return report;
}

void CheckReportFolder(const std::string& dir) {
  CheckOutputFolder(dir, {"report.json", {"hoilcd_version", "methods", "dataset"}, "report"});
}

namespace {

// " (k = 60, ...)": a method's own options as it ran, for its line in report.md; "" for none.
std::string OptionsText(const nlohmann::json& options) {
  if (!options.is_object()) return "";
  std::string out;
  for (const auto& [name, value] : options.items()) {
    out += (out.empty() ? " (" : ", ") + name + " = " +
           (value.is_string()         ? SafeText(value.get<std::string>())
            : value.is_number_float() ? ShortestDouble(value.get<double>())
                                      : value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
  }
  return out.empty() ? out : out + ")";
}

// report.json: every number of the run.
nlohmann::json ReportJson(const BenchResult& result, const Dataset& dataset, const BenchOptions& options,
                          const ReportTiming& timing, const InspectReport& inspect, const Diagnosis& diagnosis) {
  const DatasetManifest& manifest = dataset.manifest();
  nlohmann::json report = ResultsJson(result, options);
  report["hoilcd_version"] = HOILCD_VERSION;
  report["dataset"] = {{"dir", SafeText(dataset.dir())},
                       {"scene_hash", manifest.scene_hash},
                       {"seed", manifest.seed},
                       {"frames", dataset.num_frames()}};
  report["parameters"] = {{"keypoint_detector", options.keypoints.detector}};
  for (const std::string& param : options.params) {  // --param NAME=VALUE
    report["parameters"]["param"].push_back(SafeText(param));
  }
  report["inspect"] = inspect.ToJson();
  if (result.tracking_evaluated) report["tracking"] = result.tracking.ToJson();
  if (result.slam_evaluated) {
    report["slam"] = SlamSummaryJson(result.slam);
    for (const MethodSlam& m : result.slam.methods) report["methods"][m.method]["slam"] = MethodSlamJson(m);
  }
  report["features"] = {{"mean_keypoints_per_frame", result.mean_keypoints_per_frame},
                        {"mean_hoi_points_per_frame", result.mean_hoi_points_per_frame}};
  report["timing"] = {{"render_s", timing.render_s},
                      {"render_cached", timing.render_cached},
                      {"bench_s", timing.bench_s},
                      {"calibration_s", timing.calibration_s},
                      {"calibration_render_cached", timing.calibration_render_cached},
                      {"calibration_bench_cached", timing.calibration_bench_cached}};
  report["finding"] = PaperFindingSummary(result);
  if (diagnosis.evaluated) report["diagnosis"] = diagnosis.ToJson();
  report["notes"] = nlohmann::json::array();
  for (const char* note : kScoringNotes) report["notes"].push_back(note);
  for (const char* note : kMethodNotes) report["notes"].push_back(note);
  return report;
}

// queries.csv: one row per method and query.
// queries.csv: one row per method and query, each query's conditions appended (when computed).
std::string QueriesCsv(const std::vector<MethodRun>& runs, const std::vector<QueryConditions>& conditions = {}) {
  std::string csv;
  for (const MethodRun& run : runs) {
    std::istringstream lines(QueryRecordsToCsv(run.metrics.queries));
    std::string line;
    bool header = true;
    size_t query = 0;
    while (std::getline(lines, line)) {
      if (header) {
        if (csv.empty()) csv += "method," + line + (conditions.empty() ? "" : ConditionsCsvHeader()) + "\n";
        header = false;
        continue;
      }
      const std::string extra = query < conditions.size() ? ConditionsCsvRow(conditions[query]) : "";
      csv += run.name + "," + line + extra + "\n";
      ++query;
    }
  }
  return csv;
}

// MRR per stratum of the first stratification, one bar per method, chance as a grey bar.
cv::Mat StrataFigure(const std::vector<StratumRow>& strata) {
  std::vector<std::string> groups;
  std::vector<Series> series;
  for (const StratumRow& row : strata) {
    if (row.stratification != strata.front().stratification) continue;
    groups.push_back(row.stratum + " (" + std::to_string(row.queries) + ")");
    series.resize(row.methods.size() + 1);
    for (size_t m = 0; m < row.methods.size(); ++m) {
      series[m].label = row.methods[m];
      series[m].y.push_back(row.mrr[m]);
    }
    series.back().label = "chance";
    series.back().colour = chart::Grey(170);
    series.back().y.push_back(row.chance_mrr);
  }
  PlotOptions options;
  options.title = "MRR by " + strata.front().stratification + " (queries)";
  options.y_label = "MRR";
  options.width_px = std::max(options.width_px, 270 * static_cast<int>(groups.size()));  // room for the labels
  return BarPlot(groups, series, options);
}

// report.json's "gallery": the queries report.html's gallery shows (gallery_sample.h).
nlohmann::json GalleryJson(const std::vector<Query>& queries, const std::vector<size_t>& sampled) {
  nlohmann::json frames = nlohmann::json::array();
  for (size_t q : sampled) frames.push_back(queries[q].frame);
  const GallerySampling sampling;
  return {{"per_group", sampling.per_group}, {"min_gap_frames", sampling.min_gap_frames}, {"query_frames", frames}};
}

// Figures to draw: file name and how to draw it.
using FigureJobs = std::vector<std::pair<std::string, std::function<cv::Mat()>>>;

// The figures of the methods' metrics alone (any method's, run by the bench or scored outside):
// the PR curves, and MRR per lap when a lap was scored.
FigureJobs MetricFigures(const std::vector<MethodRun>& runs) {
  FigureJobs jobs;
  jobs.emplace_back("pr_curves.png", [&runs] { return PrFigure(runs); });
  const bool any_lap =
      std::any_of(runs.begin(), runs.end(), [](const MethodRun& r) { return !r.metrics.per_lap.empty(); });
  if (any_lap) {  // a sequence shorter than two laps has no scored lap to plot
    jobs.emplace_back("mrr_per_lap.png", [&runs] { return LapFigure(runs); });
  }
  return jobs;
}

// Draws and writes each figure into `dir`, in parallel (each its own file).
void WriteFigureJobs(const FigureJobs& jobs, int threads, const std::string& dir) {
  ParallelFor(static_cast<int64_t>(jobs.size()), threads, [&](int64_t i) {
    const auto& [name, draw] = jobs[static_cast<size_t>(i)];
    WritePng(dir + "/" + name, draw());
  });
}

// Draws and writes the figures into `dir`; their file names in the report's order.
std::vector<std::string> WriteFigures(const BenchResult& result, const Dataset& dataset, const BenchOptions& options,
                                      const std::string& dir) {
  // The figures, listed in the report's order.
  FigureJobs figure_jobs = MetricFigures(result.runs);
  if (!result.strata.empty()) {
    figure_jobs.emplace_back("strata_mrr.png", [&result] { return StrataFigure(result.strata); });
  }
  // Figures of the paper's methods, last registered first (fusion, dlcd, slcd).
  std::vector<const LoopClosureMethod*> paper;
  for (const auto& m : RegisteredMethods())
    if (m->FromPaper()) paper.insert(paper.begin(), m.get());
  for (const LoopClosureMethod* m : paper) {
    if (const MethodRun* run = result.Find(m->Name())) {
      figure_jobs.emplace_back("trajectory_" + m->Name() + ".png",
                               [&result, run, &dataset] { return TrajectoryFigure(result, *run, dataset); });
    }
  }
  const size_t slam_figures_at = figure_jobs.size();  // the SLAM files' names go here
  for (const LoopClosureMethod* m : paper) {
    const MethodRun* run = result.Find(m->Name());
    if (!run || m->Features() == ShownFeatures::kNone) continue;
    // Queries whose frame has features for this method show the matching (like the paper's
    // figure 6); a wall with no features makes a dull example.
    std::vector<size_t> scored;
    for (size_t i = 0; i < result.queries.size(); ++i) {
      const FrameFeatures& f = result.features[result.queries[i].frame];
      if (run->metrics.queries[i].scored && !f.Points(m->Features()).empty()) scored.push_back(i);
    }
    if (scored.empty()) {
      for (size_t i = 0; i < result.queries.size(); ++i)
        if (run->metrics.queries[i].scored) scored.push_back(i);
    }
    if (scored.empty()) continue;
    figure_jobs.emplace_back("matches_" + m->Name() + ".png", [&result, run, &dataset, scored] {
      std::vector<std::vector<MatchTile>> rows;
      for (int k = 0; k < 4 && k < static_cast<int>(scored.size()); ++k) {
        rows.push_back(MatchRow(result, *run, scored[(2 * k + 1) * scored.size() / 8], dataset));
      }
      MosaicOptions mosaic;
      mosaic.scale = 1;  // four rows of four 256x192 tiles; x2 makes multi-megabyte PNGs
      return MatchMosaic(rows, mosaic);
    });
  }
  WriteFigureJobs(figure_jobs, options.threads, dir);
  std::vector<std::string> figures;
  for (size_t i = 0; i < slam_figures_at; ++i) figures.push_back(figure_jobs[i].first);
  if (result.slam_evaluated) {
    for (const std::string& f : WriteSlamFiles(result.slam, dataset.poses(), options.slam_options.slam, dir)) {
      figures.push_back(f);
    }
  }
  for (size_t i = slam_figures_at; i < figure_jobs.size(); ++i) figures.push_back(figure_jobs[i].first);

  return figures;
}

// The 95 % intervals of every headline metric, and how they were made.
std::string IntervalsMarkdown(const std::vector<MethodRun>& runs, const BootstrapPlan& plan) {
  if (plan.resamples == 0) return "";
  std::ostringstream md;
  const auto cell = [](const Interval& i) { return "[" + Fixed(i.low) + ", " + Fixed(i.high) + "]"; };
  md << "\n### Uncertainty\n\n"
     << Fixed(100 * plan.confidence, 0) << " % intervals: a circular block bootstrap of the queries in time order ("
     << plan.resamples
     << " resamples, percentile intervals). Neighbouring queries see nearly the same view and score alike, "
        "so resampling them one by one would claim more certainty than the sequence holds: they are "
        "resampled in blocks of "
     << plan.block_queries << " queries (" << Fixed(plan.block_s, 1)
     << " s), the longest block length the per-query reciprocal ranks of any method call for "
        "(Politis & White 2004).\n\n"
     << "| method | MRR | R@1 | R@5 | R@10 | PR-AUC | R@100%P |\n|---|---|---|---|---|---|---|\n";
  for (const MethodRun& run : runs) {
    const HeadlineIntervals& i = run.intervals;
    md << "| " << SafeText(run.name) << " | " << cell(i.mrr) << " | " << cell(i.recall_at_1) << " | "
       << cell(i.recall_at_5) << " | " << cell(i.recall_at_10) << " | " << cell(i.pr_auc) << " | "
       << cell(i.recall_at_100p) << " |\n";
  }
  return md.str();
}

// Every pair of methods on MRR, the paired difference and its interval, separated pairs first;
// pairs without a query both methods scored have no difference and are left out.
std::string ComparisonsMarkdown(const std::vector<PairedComparison>& comparisons) {
  const auto scored = [](const PairedComparison& c) { return c.queries > 0; };
  if (std::none_of(comparisons.begin(), comparisons.end(), scored)) return "";
  std::ostringstream md;
  md << "\n### Paired comparisons (MRR)\n\nThe difference of per-query reciprocal ranks over the queries both "
        "methods scored, with its interval from the same resampled blocks. Where the interval holds 0, this "
        "sequence cannot tell the two methods apart.\n\n";
  for (bool separated : {true, false}) {
    for (const PairedComparison& c : comparisons) {
      if (!scored(c) || c.Separated() != separated) continue;
      md << "- " << SafeText(c.ToString()) << (separated ? "" : " (not separated)") << "\n";
    }
  }
  return md.str();
}

// What the blank-view stratum says, in words from its numbers ("" without one).
std::string BlankViewSentence(const std::vector<StratumRow>& strata) {
  int scored = 0;
  const StratumRow* blank = nullptr;
  for (const StratumRow& row : strata) {
    if (row.stratification != "view") continue;
    scored += row.queries;
    if (row.stratum == "blank view" && row.queries > 0) blank = &row;
  }
  if (blank == nullptr) return "";
  double lo = INFINITY, hi = -INFINITY;
  for (double v : blank->mrr) lo = std::min(lo, v), hi = std::max(hi, v);
  const bool no_better = hi < blank->chance_mrr + 0.05;  // within 0.05 of a random order, or below
  std::ostringstream md;
  md << "\n**Blank views:** " << blank->queries << " of " << scored << " scored queries ("
     << Fixed(100.0 * blank->queries / scored, 0) << " %) see nothing but walls, floor and ceiling within "
     << kBlankSpreadK << " K. The methods score " << Fixed(lo) << "-" << Fixed(hi) << " there, against "
     << Fixed(blank->chance_mrr) << " for a random order: "
     << (no_better ? "no method does better than chance on these queries, and every headline MRR mixes them in."
                   : "some method does better than chance even there.")
     << "\n";
  return md.str();
}

// MRR and R@1 per stratum of the queries' conditions, with what chance scores there.
std::string StrataMarkdown(const std::vector<StratumRow>& strata) {
  if (strata.empty()) return "";
  std::ostringstream md;
  md << "\n### Results by condition\n\nMRR / R@1 of each method on the queries of each stratum "
        "(conditions from the ground truth, per query in queries.csv; definitions in docs/guide/protocol.md). "
        "*chance* is the MRR of a random order of each database: a method near it is guessing there.\n\n"
     << "| stratum | queries | chance |";
  for (const std::string& m : strata.front().methods) md << " " << SafeText(m) << " |";
  md << "\n|---|---|---|";
  for (size_t m = 0; m < strata.front().methods.size(); ++m) md << "---|";
  md << "\n";
  for (const StratumRow& row : strata) {
    md << "| " << row.stratification << ": " << row.stratum << " | " << row.queries << " | " << Fixed(row.chance_mrr)
       << " |";
    for (size_t m = 0; m < row.methods.size(); ++m)
      md << " " << Fixed(row.mrr[m]) << " / " << Fixed(row.recall_at_1[m]) << " |";
    md << "\n";
  }
  md << BlankViewSentence(strata);
  return md.str();
}

// How the ground truths label the same pairs: what each adds to and removes from the other.
std::string AgreementsMarkdown(const std::vector<LabelAgreement>& agreements) {
  if (agreements.size() < 2) return "";  // odometry vs true alone: the section above says it
  std::ostringstream md;
  md << "\n### How the ground truths agree\n\n"
     << "Over the same " << agreements.front().counts.pairs << " query-database pairs: odometry and true label by "
     << "position (within the radius), overlap by the share of the query's static view the reference sees.\n\n"
     << "| a vs b | true pairs (a) | true pairs (b) | a adds | a removes | queries matched only under a | only under b "
        "|\n"
     << "|---|---|---|---|---|---|---|\n";
  for (const LabelAgreement& g : agreements) {
    const LabelDisagreement& c = g.counts;
    md << "| " << g.a << " vs " << g.b << " | " << c.pairs_true_in_a << " | " << c.pairs_true_in_b << " | "
       << c.pairs_only_in_a << " | " << c.pairs_only_in_b << " | " << c.scored_only_in_a << " | " << c.scored_only_in_b
       << " |\n";
  }
  return md.str();
}

// report.md's opening: the dataset and protocol, the results table shaped like the paper's
// Table 1 and the same scores under the other ground truth.
std::string ResultsMarkdown(const std::vector<MethodRun>& runs, const BootstrapPlan& plan,
                            const std::vector<PairedComparison>& comparisons, const std::vector<StratumRow>& strata,
                            const std::vector<RunMetrics>& per_run, const Dataset& dataset,
                            const ProtocolOptions& protocol, const std::string& other_ground_truth,
                            const LabelDisagreement& labels, const std::vector<LabelAgreement>& agreements) {
  const DatasetManifest& manifest = dataset.manifest();
  std::ostringstream md;
  md << "# hoilcd loop-closure report\n\n"
     << "Dataset `" << SafeText(dataset.dir()) << "` (" << dataset.num_frames() << " frames, seed " << manifest.seed
     << ", scene hash `" << manifest.scene_hash << "`), protocol `" << protocol.protocol << "`, ";
  if (protocol.ground_truth == "overlap") {
    md << "true match when the reference sees at least " << protocol.overlap_threshold * 100
       << " % of the query's static pixels (overlap ground truth, true poses and depth)";
  } else {
    md << "true match within " << protocol.radius_m << " m of the query's "
       << (protocol.ground_truth == "odometry" ? "odometric position (the paper's ground truth)" : "true position");
  }
  md << ", exclusion window " << protocol.exclusion_window_s << " s.\n\n"
     << "## Results (shaped like the paper's Table 1; " << protocol.ground_truth << " ground truth)\n\n"
     << "| method | MRR | R@1 | R@5 | R@10 | PR-AUC | R@100%P | ms/query (extract + match) |\n"
     << "|---|---|---|---|---|---|---|---|\n";
  for (const MethodRun& run : runs) {
    const MethodMetrics& m = run.metrics;
    md << "| " << run.name << " | " << Fixed(m.mrr) << " | " << Fixed(m.recall_at_1) << " | " << Fixed(m.recall_at_5)
       << " | " << Fixed(m.recall_at_10) << " | " << Fixed(m.pr_auc) << " | " << Fixed(m.recall_at_100p) << " | "
       << Fixed(m.ms_per_query, 2) << " (" << Fixed(m.extract_ms_mean, 2) << " + " << Fixed(m.match_ms_mean, 2)
       << ") |\n";
  }
  if (!runs.empty() && runs.front().metrics.queries_scored == 0) {
    md << "\n**No query was scored**: none has a true match in its database, so every metric above is \"-\". "
       << "Under the `laps` protocol the sequence must run past its first lap: render more frames, or use "
       << "another protocol.\n";
  } else if (!runs.empty()) {
    md << "\n"
       << runs.front().metrics.queries_scored << " queries scored, " << runs.front().metrics.queries_skipped
       << " skipped (no true match in their database).\n"
       << IntervalsMarkdown(runs, plan) << ComparisonsMarkdown(comparisons) << StrataMarkdown(strata)
       << MetricsPerRunMarkdown(per_run, plan.confidence);
  }
  md << "\n### The same scores under " << other_ground_truth << " ground truth\n\n"
     << labels.queries_differing << " of " << labels.queries << " queries have a different set of true matches ("
     << labels.pairs_differing << " query-database pairs labelled differently; " << labels.scored_only_in_a
     << " queries have a true match only under " << protocol.ground_truth << " labels, " << labels.scored_only_in_b
     << " only under " << other_ground_truth << " labels).\n\n"
     << "| method | MRR | R@1 | R@5 | PR-AUC | MRR (" << protocol.ground_truth << ") |\n|---|---|---|---|---|---|\n";
  for (const MethodRun& run : runs) {
    const MethodMetrics& m = run.other_metrics;
    md << "| " << run.name << " | " << Fixed(m.mrr) << " | " << Fixed(m.recall_at_1) << " | " << Fixed(m.recall_at_5)
       << " | " << Fixed(m.pr_auc) << " | " << Fixed(run.metrics.mrr) << " |\n";
  }
  md << AgreementsMarkdown(agreements);
  return md.str();
}

// report.md: the tables shaped like the paper's, the diagnosis, tracking, SLAM, the dataset's
// checks, and the figures.
std::string ReportMarkdown(const BenchResult& result, const Dataset& dataset, const BenchOptions& options,
                           const ReportTiming& timing, const InspectReport& inspect, const Diagnosis& diagnosis,
                           const std::vector<std::string>& figures) {
  std::ostringstream md;
  md << ResultsMarkdown(result.runs, result.bootstrap, result.comparisons, result.strata, result.per_run, dataset,
                        options.protocol, result.other_ground_truth, result.label_disagreement,
                        result.label_agreements);
  md << "\nPaper (real data): DLCD 0.222, SLCD 0.124, DLCD+SLCD 0.224.\n\n"
     << "**Finding:** " << PaperFindingSummary(result) << "\n\n"
     << DiagnosisMarkdown(result, diagnosis);
  if (result.tracking_evaluated && result.ground_truth_person_views == 0) {
    // Precision, recall and MOTA are 0/0 here; say what happened instead.
    const TrackingMetrics& t = result.tracking;
    md << "## Person tracking (DLCD front end vs ground truth)\n\n"
       << "The ground truth has no people to track; the front end reported " << t.predicted_boxes << " person boxes"
       << (t.predicted_boxes > 0 ? ", all false positives" : "") << ". Mean HOI points per frame "
       << Fixed(result.mean_hoi_points_per_frame, 1) << ", keypoints per frame "
       << Fixed(result.mean_keypoints_per_frame, 1) << ".\n\n";
  } else if (result.tracking_evaluated) {
    const TrackingMetrics& t = result.tracking;
    md << "## Person tracking (DLCD front end vs ground truth)\n\n"
       << "precision " << Fixed(t.precision) << ", recall " << Fixed(t.recall) << ", MOTA " << Fixed(t.mota)
       << ", IDF1 " << Fixed(t.idf1) << ", id switches " << t.id_switches << "; HOI points: median error "
       << Fixed(t.hoi_median_error_px, 1) << " px, " << Fixed(100 * t.hoi_fraction_within_tolerance, 1)
       << " % of visible contacts within 3 px. Mean HOI points per frame " << Fixed(result.mean_hoi_points_per_frame, 1)
       << ", keypoints per frame " << Fixed(result.mean_keypoints_per_frame, 1) << ".\n\n";
  }
  if (result.slam_evaluated) md << SlamMarkdown(result.slam, options.slam_options.slam);
  md << "## Dataset (hoilcd inspect)\n\n" << inspect.ToMarkdown();
  md << "## Methods\n\n";
  for (const MethodRun& run : result.runs) {
    md << "- `" << run.name << "`: " << FindMethod(run.name).Description() << OptionsText(run.options) << "\n";
  }
  md << "\n## Timing\n\nrender " << Fixed(timing.render_s, 1) << " s"
     << (timing.render_cached ? " (cached dataset)" : "") << ", bench " << Fixed(timing.bench_s, 1)
     << " s.\n\n## Notes\n\n";
  for (const char* note : kScoringNotes) md << "- " << note << "\n";
  for (const char* note : kMethodNotes) md << "- " << note << "\n";
  md << "\n## Figures\n\n";
  if (dataset.footprints().empty()) {
    md << "The dataset has no footprints.json (written before it existed): the trajectory figures "
          "show no obstacles.\n\n";
  }
  for (const std::string& f : figures) md << "![" << f << "](" << f << ")\n\n";
  return md.str();
}

// WriteReport with the dataset's checks already made (InspectDataset).
// Each caller has checked the folder (CheckReportFolder) before its own work.
void WriteReportInspected(const BenchResult& result, const Dataset& dataset, const BenchOptions& options,
                          const ReportTiming& timing, const std::string& dir, const InspectReport& inspect) {
  const FolderLock lock(dir, FolderLock::IfBusy::kWait);  // one writer at a time: never a mix of two reports
  const Diagnosis diagnosis = Diagnose(result);
  nlohmann::json json = ReportJson(result, dataset, options, timing, inspect, diagnosis);
  std::vector<const std::vector<QueryRecord>*> records;
  for (const MethodRun& run : result.runs) records.push_back(&run.metrics.queries);
  json["gallery"] =
      GalleryJson(result.queries, SampleGallery(records, result.conditions, StratificationsOf(result.strata)));
  WriteFileAtomic(dir + "/report.json", json.dump(2));
  WriteFileAtomic(dir + "/queries.csv", QueriesCsv(result.runs, result.conditions));
  const std::vector<std::string> figures = WriteFigures(result, dataset, options, dir);
  WriteFileAtomic(dir + "/report.md", ReportMarkdown(result, dataset, options, timing, inspect, diagnosis, figures));
  WriteFileAtomic(dir + "/report.html",
                  BenchReportHtml(result, dataset, options, {dir, figures, GallerySampling()}).html);
}

}  // namespace

void WriteReport(const BenchResult& result, const Dataset& dataset, const BenchOptions& options,
                 const ReportTiming& timing, const std::string& dir) {
  CheckReportFolder(dir);  // before the checks' work
  WriteReportInspected(result, dataset, options, timing, dir,
                       InspectDataset(dataset, options.protocol, options.threads));
}

BenchResult BenchAndWriteReport(const Dataset& dataset, BenchOptions options, ReportTiming* timing,
                                const std::string& dir, const std::function<void(SlamRunOptions*)>& before_slam) {
  CheckReportFolder(dir);                        // a folder the report may not use fails before the work
  CheckProtocolFits(dataset, options.protocol);  // as does a protocol the dataset cannot take
  // The report's dataset checks read only the dataset: they run beside the bench, on the core
  // its serial steps (ByteTrack, the pose graphs) leave idle, instead of after it. With one
  // thread asked for there is no such core: they run after the bench, on the same thread.
  const std::launch when = ResolveThreadCount(options.threads) > 1 ? std::launch::async : std::launch::deferred;
  std::future<InspectReport> inspect =
      std::async(when, [&] { return InspectDataset(dataset, options.protocol, options.threads); });
  BenchOptions scoring = options;
  scoring.slam = false;
  BenchResult result = RunBench(dataset, scoring);  // if it throws, ~future waits for the checks
  if (options.slam) {
    if (before_slam) before_slam(&options.slam_options);
    AddSlam(dataset, options, &result);
  }
  timing->bench_s = result.seconds;
  WriteReportInspected(result, dataset, options, *timing, dir, inspect.get());
  return result;
}

MethodReport EvaluateAndWriteReport(const Dataset& dataset, const Labelling& labelling, const ScoreMatrix& scores,
                                    const std::string& name, const std::string& description, const std::string& dir) {
  CheckReportFolder(dir);  // a folder the report may not use fails before the work
  const ProtocolOptions& protocol = labelling.protocol;
  const MethodReport report = EvaluateLabelled(dataset, labelling, scores, name);
  std::vector<MethodRun> runs(1);
  runs[0].name = report.name;
  runs[0].metrics = report.metrics;
  runs[0].intervals = report.intervals;
  runs[0].other_metrics = report.other_metrics;
  // The same conditions and strata as a bench report of this method.
  const std::vector<QueryConditions> conditions = ComputeQueryConditions(dataset, labelling.queries);
  const std::vector<StratumRow> strata =
      Stratify(conditions, {report.name}, {&report.metrics.queries}, DefaultStratifications());
  const std::vector<RunMetrics> per_run = MetricsPerRun(dataset.runs(), {report.name}, {&report.metrics.queries},
                                                        report.bootstrap, BootstrapOptions().seed);
  const FolderLock lock(dir, FolderLock::IfBusy::kWait);  // one writer at a time: never a mix of two reports
  nlohmann::json json = EvaluateReportJson(dataset, protocol, report, description);
  json["strata"] = StrataJson(strata);
  json["gallery"] =
      GalleryJson(labelling.queries, SampleGallery({&report.metrics.queries}, conditions, StratificationsOf(strata)));
  if (!per_run.empty()) json["recording_runs"] = MetricsPerRunJson(per_run);
  json["label_agreement"] = nlohmann::json::array();
  for (const LabelAgreement& g : labelling.agreements) json["label_agreement"].push_back(g.ToJson());
  WriteFileAtomic(dir + "/report.json", json.dump(2) + "\n");
  WriteFileAtomic(dir + "/queries.csv", QueriesCsv(runs, conditions));
  const FigureJobs figures = MetricFigures(runs);
  WriteFigureJobs(figures, /*threads=*/1, dir);
  std::ostringstream md;
  md << ResultsMarkdown(runs, report.bootstrap, {}, strata, per_run, dataset, protocol, labelling.other_ground_truth,
                        labelling.disagreement, labelling.agreements)
     << "\n## Methods\n\n- `" << SafeText(report.name) << "`: " << SafeText(description) << "\n\n## Notes\n\n";
  for (const char* note : kScoringNotes) md << "- " << note << "\n";
  md << "\n## Figures\n\n";
  for (const auto& figure : figures) md << "![" << figure.first << "](" << figure.first << ")\n\n";
  WriteFileAtomic(dir + "/report.md", md.str());
  std::vector<std::string> figure_names;
  for (const auto& figure : figures) figure_names.push_back(figure.first);
  WriteFileAtomic(dir + "/report.html",
                  EvaluateReportHtml(runs[0], report.bootstrap, labelling.queries, conditions, strata, dataset,
                                     protocol, description, {dir, figure_names, GallerySampling()})
                      .html);
  return report;
}

}  // namespace hoilcd
