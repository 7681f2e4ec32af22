#include "hoilcd/bench/evaluation/evaluate.h"

#include <cmath>

#include "hoilcd/bench/evaluation/safe_text.h"
#include "hoilcd/core/util/error.h"

namespace hoilcd {

Labelling LabelQueries(const Dataset& dataset, const ProtocolOptions& protocol) {
  if (const std::string problem = protocol.Check(); !problem.empty()) throw InputError("protocol", problem);
  Labelling l;
  l.ground_truth = protocol.ground_truth;
  l.other_ground_truth = OtherGroundTruth(protocol.ground_truth);
  l.queries = BuildQueries(dataset.poses(), protocol);
  l.other_queries = RelabelQueries(l.queries, dataset.poses(), protocol, l.other_ground_truth);
  l.disagreement = CompareLabels(l.queries, l.other_queries);
  l.label_poses = LabelPoses(dataset.poses(), l.ground_truth);
  l.other_label_poses = LabelPoses(dataset.poses(), l.other_ground_truth);
  l.to_score.resize(l.queries.size());
  for (size_t i = 0; i < l.queries.size(); ++i) {
    l.to_score[i] = l.queries[i].NumTrueMatches() > 0 || l.other_queries[i].NumTrueMatches() > 0;
  }
  return l;
}

MethodReport EvaluateQueryScores(const Labelling& labelling, const std::string& name,
                                 const std::vector<std::vector<double>>& scores) {
  MethodReport r;
  r.name = SafeText(name);  // the name every report file writes
  r.metrics = ComputeMetrics(labelling.queries, scores, labelling.label_poses);
  r.other_metrics = ComputeMetrics(labelling.other_queries, scores, labelling.other_label_poses);
  return r;
}

std::vector<std::vector<double>> QueryScores(const Labelling& labelling, const ScoreMatrix& matrix,
                                             int dataset_frames) {
  if (matrix.frames != dataset_frames ||
      matrix.values.size() != static_cast<size_t>(matrix.frames) * static_cast<size_t>(matrix.frames)) {
    throw InputError("scores", "a " + std::to_string(matrix.frames) + " x " + std::to_string(matrix.frames) +
                                   " matrix: expected " + std::to_string(dataset_frames) + " x " +
                                   std::to_string(dataset_frames) + " (the dataset's frames)");
  }
  std::vector<std::vector<double>> out(labelling.queries.size());
  for (size_t i = 0; i < labelling.queries.size(); ++i) {
    const Query& q = labelling.queries[i];
    double lowest = 0;
    bool any = false;
    for (int r : q.database) {
      const double v = matrix.At(q.frame, r);
      if (std::isnan(v)) continue;
      if (!std::isfinite(v)) {
        throw InputError("scores", "pair query " + std::to_string(q.frame) + ", reference " + std::to_string(r) +
                                       " is infinite: expected a finite score, or NaN for unscored");
      }
      lowest = any ? std::min(lowest, v) : v;
      any = true;
    }
    // Below every scored pair of this query; scores files cap magnitudes at 1e300, so this is finite.
    const double unscored = any ? lowest - 1 - std::fabs(lowest) : 0;
    for (int r : q.database) {
      const double v = matrix.At(q.frame, r);
      out[i].push_back(std::isnan(v) ? unscored : v);
    }
  }
  return out;
}

MethodReport Evaluate(const Dataset& dataset, const ScoreMatrix& scores, const std::string& name,
                      const ProtocolOptions& protocol) {
  const Labelling labelling = LabelQueries(dataset, protocol);
  return EvaluateQueryScores(labelling, name, QueryScores(labelling, scores, dataset.num_frames()));
}

nlohmann::json EvaluateReportJson(const Dataset& dataset, const ProtocolOptions& protocol,
                                  const MethodReport& report, const std::string& description) {
  nlohmann::json j;
  j["hoilcd_version"] = HOILCD_VERSION;
  j["dataset"] = {{"dir", SafeText(dataset.dir())}, {"scene_hash", dataset.manifest().scene_hash},
                  {"seed", dataset.manifest().seed}, {"frames", dataset.num_frames()}};
  j["protocol"] = {{"protocol", protocol.protocol}, {"radius_m", protocol.radius_m},
                   {"ground_truth", protocol.ground_truth},
                   {"heading_tolerance_deg", protocol.heading_tolerance_deg},
                   {"exclusion_window_s", protocol.exclusion_window_s}};
  nlohmann::json m = report.metrics.ToJson();
  m["description"] = SafeText(description);
  const std::string name = SafeText(report.name);  // already safe from EvaluateQueryScores, unless built elsewhere
  j["methods"][name] = m;
  j["other_ground_truth"] = {{"ground_truth", OtherGroundTruth(protocol.ground_truth)},
                             {"methods", {{name, report.other_metrics.ToJson()}}}};
  return j;
}

}  // namespace hoilcd
