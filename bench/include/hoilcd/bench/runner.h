// Runs loop-closure methods over a dataset folder in named steps: label the protocol's queries,
// run the front ends the chosen methods need (front_ends.h), score every method
// (loop_closure_method.h), compute metrics (evaluate.h); plus the person-tracking quality of the
// DLCD front end against the ground truth. The report module writes what this returns.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "hoilcd/bench/metrics.h"
#include "hoilcd/bench/protocol.h"
#include "hoilcd/bench/slam_run.h"
#include "hoilcd/bench/tracking_metrics.h"
#include "hoilcd/core/byte_tracker.h"
#include "hoilcd/core/dataset.h"
#include "hoilcd/core/hoi_features.h"
#include "hoilcd/core/homography_ransac.h"
#include "hoilcd/core/keypoints.h"
#include "hoilcd/core/matching.h"
#include "hoilcd/core/person_detection.h"
#include "hoilcd/core/temporal_consistency.h"
#include "hoilcd/core/thumbnail_baseline.h"
#include "hoilcd/core/track_aware_matching.h"

namespace hoilcd {

// Tracking is scored on people at least 20 % visible with a visible box at least 16 px high;
// others are neither missed nor false positives (a thermal detector cannot see through a person
// or a chair back, nor find a sliver at the image edge).
inline TrackingMetricsOptions DefaultTrackingMetricsOptions() {
  TrackingMetricsOptions o;
  o.min_visible_fraction = 0.2;
  o.min_box_height_px = 16;  // slivers at the image edge are fully "visible" but undetectable
  return o;
}

struct BenchOptions {
  std::vector<std::string> methods;      // names from methods.h (empty: DefaultMethods())
  // --param NAME=VALUE: "<method>.<field>" or "<front end>.<field>" (method_params.h).
  std::vector<std::string> params;
  ProtocolOptions protocol;
  MatchOptions match;
  RansacOptions ransac;
  int lo_refits = 2;                     // least-squares refits of the -lo variants
  KeypointOptions keypoints;
  PersonDetectorOptions detector;
  ByteTrackOptions tracker;
  HoiOptions hoi;
  TrackAwareOptions track_aware;
  ThumbnailOptions thumbnail;
  SeqSlamOptions sequence;               // sequence matching of thumb-seq
  TemporalConsistencyOptions temporal;
  double rrf_k = 0.0;                    // reciprocal rank fusion constant (paper: 0)
  TrackingMetricsOptions tracking_metrics = DefaultTrackingMetricsOptions();
  int threads = 0;                       // 0 = every core
  bool slam = false;                     // run the SLAM back end over every method's loops (slam_run.h)
  SlamRunOptions slam_options;
  std::string Check() const;
};

// Features a method computed for one frame (for the report's match pictures).
struct FrameFeatures {
  std::vector<Point2> keypoints;   // SLCD
  std::vector<HoiFeature> hoi;     // DLCD
};

struct MethodRun {
  std::string name;
  MethodMetrics metrics;        // under the chosen ground truth (protocol.ground_truth)
  MethodMetrics other_metrics;  // the same scores under the other ground truth
  std::vector<std::vector<double>> scores;  // per query, parallel to Query::database
};

struct BenchResult {
  std::vector<Query> queries;              // labelled with protocol.ground_truth
  std::string ground_truth;                // protocol.ground_truth: "odometry" or "true"
  std::string other_ground_truth;          // the other one
  std::vector<Query> other_queries;        // the same queries labelled with other_ground_truth
  LabelDisagreement label_disagreement;    // queries vs other_queries
  std::vector<MethodRun> runs;             // in the order asked for
  std::vector<FrameFeatures> features;     // per frame
  TrackingMetrics tracking;                // DLCD front end vs persons.json (when DLCD ran)
  bool tracking_evaluated = false;
  double mean_hoi_points_per_frame = 0;
  double mean_keypoints_per_frame = 0;
  int64_t ground_truth_person_views = 0;   // person records in persons.json (all frames)
  SlamResult slam;                         // when BenchOptions::slam
  bool slam_evaluated = false;
  double seconds = 0;                      // wall time of RunBench
  const MethodRun* Find(const std::string& name) const;
};

BenchResult RunBench(const Dataset& dataset, const BenchOptions& options);

// RunBench's last step, on its own: the pose graphs of each method's loops (options.slam_options)
// into result->slam. For a result scored with slam off; adds its time to result->seconds.
void AddSlam(const Dataset& dataset, const BenchOptions& options, BenchResult* result);

}  // namespace hoilcd
