// The benchmark's protocol, labels and metrics applied to any method's scores: from RunBench, a
// scores file (`hoilcd evaluate`) or Python. One method's figures come out as report.json gives
// them under methods.<name>; both ground truths are measured, as in the bench.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hoilcd/bench/evaluation/bootstrap.h"
#include "hoilcd/bench/evaluation/metrics.h"
#include "hoilcd/bench/evaluation/protocol.h"
#include "hoilcd/bench/evaluation/scores_file.h"
#include "hoilcd/core/dataset/dataset.h"

namespace hoilcd {

// How two of the ground truths label the same pairs: `a` against `b`.
struct LabelAgreement {
  std::string a, b;  // "odometry", "true", "overlap"
  LabelDisagreement counts;
  nlohmann::json ToJson() const;
};

// A dataset's queries labelled under the chosen ground truth and under the other one.
struct Labelling {
  ProtocolOptions protocol;             // what labelled them
  double frame_rate_hz = 0;             // the dataset's (the bootstrap's blocks are in seconds)
  std::string ground_truth;             // protocol.ground_truth: "odometry", "true" or "overlap"
  std::string other_ground_truth;       // OtherGroundTruth(ground_truth)
  std::vector<Query> queries;           // labelled with ground_truth
  std::vector<Query> other_queries;     // the same queries and databases, other labels
  std::vector<PoseRecord> label_poses;  // LabelPoses(poses, ground_truth)
  std::vector<PoseRecord> other_label_poses;
  LabelDisagreement disagreement;  // queries vs other_queries
  // Every pair of the ground truths computed: true vs odometry, and with overlap labels (ground
  // truth overlap) overlap vs odometry and overlap vs true.
  std::vector<LabelAgreement> agreements;
  // Queries worth scoring: a true match under either labelling, so both can be measured.
  std::vector<bool> to_score;
};

// InputError("protocol", ...) when protocol.Check() fails, and CheckProtocolFits' error. Overlap
// labels read the EXRs on `threads` threads (0: every CPU).
Labelling LabelQueries(const Dataset& dataset, const ProtocolOptions& protocol, int threads = 0);

// Empty when a query has a true match under labelling.ground_truth. Else why none has, in words
// a user can act on ("no query has a true match, so MRR, Recall@K and PR are undefined: the
// robot's 300 frames never complete its first lap ..."): the metrics are undefined.
std::string NoTrueMatchReason(const Labelling& labelling);

// One method's figures under both labellings (timing left NaN: the caller sets it if known).
struct MethodReport {
  std::string name;                   // as given, through SafeText (safe_text.h)
  MethodMetrics metrics;              // under Labelling::ground_truth
  MethodMetrics other_metrics;        // under Labelling::other_ground_truth
  BootstrapPlan bootstrap;            // how the intervals resampled the queries (EvaluateLabelled)
  HeadlineIntervals intervals;        // of metrics (EvaluateLabelled)
  std::vector<std::string> warnings;  // about the scores: queries with none of their pairs scored
};

// scores[i] parallel to labelling.queries[i].database, finite. No intervals: they need every
// method's records for one plan (the runner's step 5; EvaluateLabelled's own for one method).
MethodReport EvaluateQueryScores(const Labelling& labelling, const std::string& name,
                                 const std::vector<std::vector<double>>& scores);

// Each query's database scores picked out of `matrix`; an unscored (NaN) pair ranks below every
// scored pair of its query (all unscored: all tied, each warned about in `warnings`). InputError
// naming matrix.source when the matrix is not frames x frames of the labelled dataset, holds an
// infinity, or scores none of the pairs of the queries with a true match (their metrics would be
// those of a random order).
std::vector<std::vector<double>> QueryScores(const Labelling& labelling, const ScoreMatrix& matrix, int dataset_frames,
                                             std::vector<std::string>* warnings = nullptr);

// NoTrueMatchReason (an InputError naming the dataset) + QueryScores + EvaluateQueryScores.
MethodReport EvaluateLabelled(const Dataset& dataset, const Labelling& labelling, const ScoreMatrix& scores,
                              const std::string& name);

// LabelQueries + EvaluateLabelled.
MethodReport Evaluate(const Dataset& dataset, const ScoreMatrix& scores, const std::string& name,
                      const ProtocolOptions& protocol);

// A report.json of one evaluated method, shaped like the bench's (hoilcd_version, dataset,
// protocol, methods.<name>, other_ground_truth.methods.<name>) so --baseline can read either.
nlohmann::json EvaluateReportJson(const Dataset& dataset, const ProtocolOptions& protocol, const MethodReport& report,
                                  const std::string& description);

}  // namespace hoilcd
