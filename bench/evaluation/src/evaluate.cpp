#include "hoilcd/bench/evaluation/evaluate.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "hoilcd/bench/evaluation/overlap.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/memory.h"
#include "hoilcd/core/util/safe_text.h"
#include "hoilcd/core/util/text.h"

namespace hoilcd {

nlohmann::json LabelAgreement::ToJson() const {
  return {{"a", a},
          {"b", b},
          {"pairs", counts.pairs},
          {"pairs_true_in_a", counts.pairs_true_in_a},
          {"pairs_true_in_b", counts.pairs_true_in_b},
          {"pairs_only_in_a", counts.pairs_only_in_a},
          {"pairs_only_in_b", counts.pairs_only_in_b},
          {"queries", counts.queries},
          {"queries_with_match_only_in_a", counts.scored_only_in_a},
          {"queries_with_match_only_in_b", counts.scored_only_in_b}};
}

Labelling LabelQueries(const Dataset& dataset, const ProtocolOptions& protocol, int threads) {
  if (const std::string problem = protocol.Check(); !problem.empty()) throw InputError("protocol", problem);
  CheckProtocolFits(dataset, protocol);
  Labelling l;
  l.protocol = protocol;
  l.frame_rate_hz = dataset.manifest().frame_rate_hz;
  l.ground_truth = protocol.ground_truth;
  l.other_ground_truth = OtherGroundTruth(protocol.ground_truth);
  // At most every earlier frame is a query's database: n^2 / 2 pairs, each a frame index and a
  // label, under both ground truths.
  const double frames = static_cast<double>(dataset.poses().size());
  CheckAllocation(frames * frames / 2 * (sizeof(int) + sizeof(uint8_t)) * 2, SafeText(dataset.dir()),
                  "labelling the query pairs of " + std::to_string(dataset.poses().size()) + " frames");
  l.queries = BuildQueries(dataset.poses(), protocol);
  l.other_queries = RelabelQueries(l.queries, dataset.poses(), protocol, l.other_ground_truth);
  std::vector<Query> by_truth;  // overlap: BuildQueries labels its pairs by true position
  if (protocol.ground_truth == "overlap") {
    by_truth = l.queries;
    l.queries = OverlapLabels(dataset, by_truth, protocol, threads);
  }
  l.disagreement = CompareLabels(l.queries, l.other_queries);
  if (protocol.ground_truth == "overlap") {
    l.agreements = {{"true", "odometry", CompareLabels(by_truth, l.other_queries)},
                    {"overlap", "odometry", l.disagreement},
                    {"overlap", "true", CompareLabels(l.queries, by_truth)}};
  } else if (protocol.ground_truth == "true") {
    l.agreements = {{"true", "odometry", l.disagreement}};
  } else {
    l.agreements = {{"true", "odometry", CompareLabels(l.other_queries, l.queries)}};
  }
  l.label_poses = LabelPoses(dataset.poses(), l.ground_truth);
  l.other_label_poses = LabelPoses(dataset.poses(), l.other_ground_truth);
  l.to_score.resize(l.queries.size());
  for (size_t i = 0; i < l.queries.size(); ++i) {
    l.to_score[i] = l.queries[i].NumTrueMatches() > 0 || l.other_queries[i].NumTrueMatches() > 0;
  }
  return l;
}

std::string NoTrueMatchReason(const Labelling& labelling) {
  const auto has_true_match = [](const Query& q) { return q.NumTrueMatches() > 0; };
  if (std::any_of(labelling.queries.begin(), labelling.queries.end(), has_true_match)) return "";
  const ProtocolOptions& p = labelling.protocol;
  const std::vector<PoseRecord>& poses = labelling.label_poses;
  const std::string positions = labelling.ground_truth == "odometry" ? "odometric" : "true";
  std::ostringstream why;
  why << "no query has a true match, so MRR, Recall@K and PR are undefined: ";
  const bool overlap = labelling.ground_truth == "overlap";
  std::ostringstream match;  // what a query does to a true match: "[lies] within 0.2 m of"
  if (overlap) {
    match << p.overlap_threshold * 100 << " % of its static view with";
  } else {
    match << "within " << p.radius_m << " m";
    if (p.heading_tolerance_deg >= 0) match << " and " << p.heading_tolerance_deg << " deg of heading";
    match << " of";
  }
  const std::string larger = overlap ? "a lower --overlap-threshold" : "a larger --radius";
  if (p.protocol == "laps" && labelling.queries.empty()) {
    double turned_rad = 0;
    for (size_t i = 1; i < poses.size(); ++i) {
      turned_rad += std::remainder(poses[i].theta_rad - poses[i - 1].theta_rad, 2 * M_PI);
    }
    why << "the laps protocol queries the laps after the first, and the " << poses.size()
        << " frames never complete a first lap (the " << positions << " heading turns "
        << std::lround(std::fabs(turned_rad) * 180 / M_PI) << " deg of 360); render more frames, or use --protocol "
        << "revisit";
  } else if (p.protocol == "laps") {
    why << "none of the " << labelling.queries.size() << " frames after the first lap "
        << (overlap ? "shares " : "lies ") << match.str() << " a first-lap frame by the " << positions
        << " poses (frames within " << p.exclusion_window_s << " s of a query are left out); " << larger
        << " may find some";
  } else if (p.protocol == "runs") {
    why << "none of the " << labelling.queries.size() << " frames of the later recording runs "
        << (overlap ? "shares " : "lies ") << match.str() << " a frame of the first run by the " << positions
        << " poses; " << larger << " may find some";
  } else {
    why << "no frame " << (overlap ? "shares " : "comes back ") << match.str() << " a frame more than "
        << p.exclusion_window_s << " s older by the " << positions << " poses; render more frames, or " << larger
        << " or a shorter "
        << "--exclusion-window may find some";
  }
  const auto other = std::count_if(labelling.other_queries.begin(), labelling.other_queries.end(), has_true_match);
  if (other > 0) {
    why << " (with --ground-truth " << labelling.other_ground_truth << ", " << other << " queries have one)";
  }
  return why.str();
}

MethodReport EvaluateQueryScores(const Labelling& labelling, const std::string& name,
                                 const std::vector<std::vector<double>>& scores) {
  MethodReport r;
  r.name = SafeText(name);  // the name every report file writes
  r.metrics = ComputeMetrics(labelling.queries, scores, labelling.label_poses);
  r.other_metrics = ComputeMetrics(labelling.other_queries, scores, labelling.other_label_poses);
  return r;
}

std::vector<std::vector<double>> QueryScores(const Labelling& labelling, const ScoreMatrix& matrix, int dataset_frames,
                                             std::vector<std::string>* warnings) {
  if (matrix.frames != dataset_frames ||
      matrix.values.size() != static_cast<size_t>(matrix.frames) * static_cast<size_t>(matrix.frames)) {
    throw InputError(matrix.source, "a " + std::to_string(matrix.frames) + " x " + std::to_string(matrix.frames) +
                                        " matrix: expected " + std::to_string(dataset_frames) + " x " +
                                        std::to_string(dataset_frames) + " (the dataset's frames)");
  }
  std::vector<std::vector<double>> out(labelling.queries.size());
  int64_t pairs = 0, pairs_scored = 0;  // of the queries worth scoring
  int queries = 0, queries_unscored = 0;
  for (size_t i = 0; i < labelling.queries.size(); ++i) {
    const Query& q = labelling.queries[i];
    double lowest = 0;
    bool any = false;
    for (int r : q.database) {
      const double v = matrix.At(q.frame, r);
      if (std::isnan(v)) continue;
      if (!(std::fabs(v) <= kMaxAbsScore)) {
        const std::string pair = "pair query " + std::to_string(q.frame) + ", reference " + std::to_string(r);
        if (std::isinf(v))
          throw InputError(matrix.source, pair + " is infinite: expected a finite score, or NaN for unscored");
        throw InputError(matrix.source, pair + " is " + ShortestDouble(v) + ": expected a score of magnitude at most " +
                                            "1e300, or NaN for unscored");
      }
      lowest = any ? std::min(lowest, v) : v;
      any = true;
      pairs_scored += labelling.to_score[i] ? 1 : 0;
    }
    if (labelling.to_score[i]) {
      pairs += static_cast<int64_t>(q.database.size());
      ++queries;
      queries_unscored += any ? 0 : 1;
    }
    // Below every scored pair of this query; magnitudes are at most kMaxAbsScore, so this is finite.
    const double unscored = any ? lowest - 1 - std::fabs(lowest) : 0;
    for (int r : q.database) {
      const double v = matrix.At(q.frame, r);
      out[i].push_back(std::isnan(v) ? unscored : v);
    }
  }
  if (pairs > 0 && pairs_scored == 0) {
    throw InputError(matrix.source, "scores none of the " + std::to_string(pairs) + " (query, database frame) " +
                                        "pairs of the " + std::to_string(queries) + " queries with a true match: " +
                                        "expected scores of those pairs (without any, every database would rank " +
                                        "in a random order)");
  }
  if (queries_unscored > 0 && warnings != nullptr) {
    warnings->push_back(matrix.source + ": " + std::to_string(queries_unscored) + " of the " + std::to_string(queries) +
                        " queries with a true match have no scored pair in their " +
                        "database; each ranks it all tied (the expected rank of a random order)");
  }
  return out;
}

MethodReport EvaluateLabelled(const Dataset& dataset, const Labelling& labelling, const ScoreMatrix& scores,
                              const std::string& name) {
  if (const std::string why = NoTrueMatchReason(labelling); !why.empty()) throw InputError(dataset.dir(), why);
  std::vector<std::string> warnings;
  const std::vector<std::vector<double>> query_scores = QueryScores(labelling, scores, dataset.num_frames(), &warnings);
  MethodReport report = EvaluateQueryScores(labelling, name, query_scores);
  report.warnings = std::move(warnings);
  const BootstrapOptions bootstrap;
  report.bootstrap = PlanBootstrap({&report.metrics.queries}, labelling.frame_rate_hz, bootstrap);
  report.intervals = BootstrapHeadline(report.metrics.queries, report.bootstrap, bootstrap.seed);
  return report;
}

MethodReport Evaluate(const Dataset& dataset, const ScoreMatrix& scores, const std::string& name,
                      const ProtocolOptions& protocol) {
  return EvaluateLabelled(dataset, LabelQueries(dataset, protocol), scores, name);
}

nlohmann::json EvaluateReportJson(const Dataset& dataset, const ProtocolOptions& protocol, const MethodReport& report,
                                  const std::string& description) {
  nlohmann::json j;
  j["hoilcd_version"] = HOILCD_VERSION;
  j["dataset"] = {{"dir", SafeText(dataset.dir())},
                  {"scene_hash", dataset.manifest().scene_hash},
                  {"seed", dataset.manifest().seed},
                  {"frames", dataset.num_frames()}};
  j["protocol"] = ProtocolOptions::Table().ToJson(protocol);
  j["bootstrap"] = report.bootstrap.ToJson();
  nlohmann::json m = report.metrics.ToJson();
  m["description"] = SafeText(description);
  m["intervals"] = report.intervals.ToJson();
  const std::string name = SafeText(report.name);  // already safe from EvaluateQueryScores, unless built elsewhere
  j["methods"][name] = m;
  j["other_ground_truth"] = {{"ground_truth", OtherGroundTruth(protocol.ground_truth)},
                             {"methods", {{name, report.other_metrics.ToJson()}}}};
  return j;
}

}  // namespace hoilcd
