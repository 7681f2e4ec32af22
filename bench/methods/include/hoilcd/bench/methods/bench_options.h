// What a bench run is asked to do: which methods, the protocol, and every method's and front
// end's options (the paper's defaults). The runner (runner.h) and the methods read it.
#pragma once

#include <string>
#include <vector>

#include "hoilcd/bench/evaluation/protocol.h"
#include "hoilcd/bench/evaluation/tracking_metrics.h"
#include "hoilcd/bench/slam/slam_run.h"
#include "hoilcd/core/features/hoi_features.h"
#include "hoilcd/core/features/keypoints.h"
#include "hoilcd/core/features/person_detection.h"
#include "hoilcd/core/matching/matching.h"
#include "hoilcd/core/matching/track_aware_matching.h"
#include "hoilcd/core/optim/ransac.h"
#include "hoilcd/core/place_recognition/temporal_consistency.h"
#include "hoilcd/core/place_recognition/thumbnail_baseline.h"
#include "hoilcd/core/tracking/byte_tracker.h"

namespace hoilcd {

// Defaults and ranges: Table() in bench_options.cpp, each member struct's from its own table.
struct BenchOptions {
  // Lists, not table fields (empty when constructed); the table's rules check them.
  std::vector<std::string> methods;  // names from methods.h (empty: DefaultMethods())
  // --param NAME=VALUE: "<method>.<field>" or "<front end>.<field>" (method_params.h).
  std::vector<std::string> params;
  ProtocolOptions protocol;
  MatchOptions match;
  RansacOptions ransac;
  int lo_refits;                     // least-squares refits of the -lo variants
  KeypointOptions keypoints;
  PersonDetectorOptions detector;
  ByteTrackOptions tracker;
  HoiOptions hoi;
  TrackAwareOptions track_aware;
  ThumbnailOptions thumbnail;
  SeqSlamOptions sequence;           // sequence matching of thumb-seq
  TemporalConsistencyOptions temporal;
  double rrf_k;                      // reciprocal rank fusion constant (paper: 0)
  // The bench's own defaults (its table): people at least 20 % visible with a visible box at
  // least 16 px high are scored; others are neither missed nor false positives (a thermal detector
  // cannot see through a person or a chair back, nor find a sliver at the image edge).
  TrackingMetricsOptions tracking_metrics;
  int threads;                       // 0 = every core
  bool slam;                         // run the SLAM back end over every method's loops (slam_run.h)
  SlamRunOptions slam_options;

  BenchOptions();  // the registered defaults
  // Every field once (member structs through their own tables): name, default, unit, range.
  static const OptionTable<BenchOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...", an unknown method, a bad --param).
  std::string Check() const;
};

}  // namespace hoilcd
