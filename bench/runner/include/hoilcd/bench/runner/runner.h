// Runs loop-closure methods over a dataset folder in named steps: label the protocol's queries,
// run the front ends the chosen methods need (front_ends.h), score every method
// (loop_closure_method.h), compute metrics (evaluate.h); plus the person-tracking quality of the
// DLCD front end against the ground truth. The report module writes what this returns.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hoilcd/bench/evaluation/bootstrap.h"
#include "hoilcd/bench/evaluation/evaluate.h"
#include "hoilcd/bench/evaluation/metrics.h"
#include "hoilcd/bench/evaluation/protocol.h"
#include "hoilcd/bench/evaluation/query_conditions.h"
#include "hoilcd/bench/evaluation/run_metrics.h"
#include "hoilcd/bench/evaluation/tracking_metrics.h"
#include "hoilcd/bench/methods/bench_options.h"
#include "hoilcd/bench/methods/loop_closure_method.h"
#include "hoilcd/bench/slam/slam_run.h"
#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/features/hoi_features.h"
#include "hoilcd/core/geometry/point.h"

namespace hoilcd {

// The point front ends' features of one frame (for the report's match pictures); empty for a
// front end that did not run.
struct FrameFeatures {
  std::vector<Point2> keypoints;        // SLCD's (FrontEnd::kKeypoints)
  std::vector<HoiFeature> hoi;          // DLCD's (FrontEnd::kPersons)
  std::vector<Point2> ideal_keypoints;  // slcd-ideal's (FrontEnd::kIdealKeypoints)
  std::vector<HoiFeature> true_hoi;     // dlcd-oracle's (FrontEnd::kTruePersons)

  // The points a method with these Features() matches, in feature order (empty for kNone).
  std::vector<Point2> Points(ShownFeatures shown) const;
  // The same HOI points with their track ids when IsHoi(shown); else empty.
  const std::vector<HoiFeature>& Hoi(ShownFeatures shown) const;
};

struct MethodRun {
  std::string name;
  MethodMetrics metrics;                    // under the chosen ground truth (protocol.ground_truth)
  HeadlineIntervals intervals;              // of metrics (BenchResult::bootstrap says how)
  MethodMetrics other_metrics;              // the same scores under the other ground truth
  std::vector<std::vector<double>> scores;  // per query, parallel to Query::database
  nlohmann::json options;                   // the method's own options as it ran (method_options.h); null: none
};

struct BenchResult {
  std::vector<Query> queries;                    // labelled with protocol.ground_truth
  std::string ground_truth;                      // protocol.ground_truth: "odometry" or "true"
  std::string other_ground_truth;                // the other one
  std::vector<Query> other_queries;              // the same queries labelled with other_ground_truth
  LabelDisagreement label_disagreement;          // queries vs other_queries
  std::vector<LabelAgreement> label_agreements;  // Labelling::agreements: how the ground truths differ
  std::string no_true_match;                     // NoTrueMatchReason: empty unless no query has a true match
  std::vector<MethodRun> runs;                   // in the order asked for
  // Optional methods left out, each "<method>: <why>" (the dataset lacks the ground truth it needs).
  std::vector<std::string> skipped;
  BootstrapPlan bootstrap;                    // how the intervals resampled the queries
  std::vector<PairedComparison> comparisons;  // MRR of every pair of runs, in run order
  std::vector<QueryConditions> conditions;    // per query, parallel to queries
  std::vector<StratumRow> strata;             // every run's MRR and R@1 per stratum (options.strata)
  std::vector<RunMetrics> per_run;            // per recording run of the dataset (none for one run)
  std::vector<FrameFeatures> features;        // per frame
  TrackingMetrics tracking;                   // DLCD front end vs persons.json (when DLCD ran)
  bool tracking_evaluated = false;
  double mean_hoi_points_per_frame = 0;
  double mean_keypoints_per_frame = 0;
  int64_t ground_truth_person_views = 0;  // person records in persons.json (all frames)
  SlamResult slam;                        // when BenchOptions::slam
  bool slam_evaluated = false;
  double seconds = 0;  // wall time of RunBench
  const MethodRun* Find(const std::string& name) const;
};

BenchResult RunBench(const Dataset& dataset, const BenchOptions& options);

// RunBench's last step, on its own: the pose graphs of each method's loops (options.slam_options)
// into result->slam. For a result scored with slam off; adds its time to result->seconds.
void AddSlam(const Dataset& dataset, const BenchOptions& options, BenchResult* result);

}  // namespace hoilcd
