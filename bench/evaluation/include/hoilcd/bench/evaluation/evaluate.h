// The benchmark's protocol, labels and metrics applied to any method's scores: from RunBench, a
// scores file (`hoilcd evaluate`) or Python. One method's figures come out as report.json gives
// them under methods.<name>; both ground truths are measured, as in the bench.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hoilcd/bench/evaluation/metrics.h"
#include "hoilcd/bench/evaluation/protocol.h"
#include "hoilcd/bench/evaluation/scores_file.h"
#include "hoilcd/core/dataset/dataset.h"

namespace hoilcd {

// A dataset's queries labelled under the chosen ground truth and under the other one.
struct Labelling {
  std::string ground_truth;             // protocol.ground_truth: "odometry" or "true"
  std::string other_ground_truth;       // the other one
  std::vector<Query> queries;           // labelled with ground_truth
  std::vector<Query> other_queries;     // the same queries and databases, other labels
  std::vector<PoseRecord> label_poses;  // LabelPoses(poses, ground_truth)
  std::vector<PoseRecord> other_label_poses;
  LabelDisagreement disagreement;       // queries vs other_queries
  // Queries worth scoring: a true match under either labelling, so both can be measured.
  std::vector<bool> to_score;
};

// InputError("protocol", ...) when protocol.Check() fails.
Labelling LabelQueries(const Dataset& dataset, const ProtocolOptions& protocol);

// One method's figures under both labellings (timing left NaN: the caller sets it if known).
struct MethodReport {
  std::string name;             // as given, through SafeText (safe_text.h)
  MethodMetrics metrics;        // under Labelling::ground_truth
  MethodMetrics other_metrics;  // under Labelling::other_ground_truth
};

// scores[i] parallel to labelling.queries[i].database, finite.
MethodReport EvaluateQueryScores(const Labelling& labelling, const std::string& name,
                                 const std::vector<std::vector<double>>& scores);

// Each query's database scores picked out of `matrix`; an unscored (NaN) pair ranks below every
// scored pair of its query (all unscored: all tied). InputError when the matrix is not
// frames x frames of the labelled dataset.
std::vector<std::vector<double>> QueryScores(const Labelling& labelling, const ScoreMatrix& matrix,
                                             int dataset_frames);

// LabelQueries + QueryScores + EvaluateQueryScores.
MethodReport Evaluate(const Dataset& dataset, const ScoreMatrix& scores, const std::string& name,
                      const ProtocolOptions& protocol);

// A report.json of one evaluated method, shaped like the bench's (hoilcd_version, dataset,
// protocol, methods.<name>, other_ground_truth.methods.<name>) so --baseline can read either.
nlohmann::json EvaluateReportJson(const Dataset& dataset, const ProtocolOptions& protocol,
                                  const MethodReport& report, const std::string& description);

}  // namespace hoilcd
