// What a bench run is asked to do: which methods, the protocol, the shared front ends' options
// and the --param values. Each method's own options live with the method (method_options.h);
// the runner sets its --param values on them. The runner (runner.h) and the methods read this.
#pragma once

#include <string>
#include <vector>

#include "hoilcd/bench/evaluation/bootstrap.h"
#include "hoilcd/bench/evaluation/protocol.h"
#include "hoilcd/bench/evaluation/query_conditions.h"
#include "hoilcd/bench/evaluation/tracking_metrics.h"
#include "hoilcd/bench/slam/slam_run.h"
#include "hoilcd/core/features/hoi_features.h"
#include "hoilcd/core/features/keypoints.h"
#include "hoilcd/core/features/person_detection.h"
#include "hoilcd/core/place_recognition/thumbnail_baseline.h"
#include "hoilcd/core/tracking/byte_tracker.h"

namespace hoilcd {

// Defaults and ranges: Table() in bench_options.cpp, each member struct's from its own table.
struct BenchOptions {
  // Lists, not table fields (empty when constructed); the table's rules check them.
  std::vector<std::string> methods;  // names from methods.h (empty: DefaultMethods())
  // Those of `methods` that came in through "all", "paper" or the default, not by name: one the
  // dataset lacks the ground truth for (an oracle's) is left out with a note, where a named one
  // is an InputError.
  std::vector<std::string> optional_methods;
  // --param NAME=VALUE: "<method>.<field>" or "<front end>.<field>" (method_params.h); the only
  // way to set a method's own options.
  std::vector<std::string> params;
  // Stratifications of the report (query_conditions.h StratificationNames(); empty: the default).
  std::vector<std::string> strata;
  ProtocolOptions protocol;
  BootstrapOptions bootstrap;  // the metrics' intervals (blocks span protocol.exclusion_window_s)
  KeypointOptions keypoints;
  PersonDetectorOptions detector;
  ByteTrackOptions tracker;
  HoiOptions hoi;
  ThumbnailOptions thumbnail;
  // The bench's own defaults (its table): people at least 20 % visible with a visible box at
  // least 16 px high are scored; others are neither missed nor false positives (a thermal detector
  // cannot see through a person or a chair back, nor find a sliver at the image edge).
  TrackingMetricsOptions tracking_metrics;
  int threads;  // 0 = every core
  bool slam;    // run the SLAM back end over every method's loops (slam_run.h)
  SlamRunOptions slam_options;

  BenchOptions();  // the registered defaults
  // Every field once (member structs through their own tables): name, default, unit, range.
  static const OptionTable<BenchOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...", an unknown method, a bad --param).
  std::string Check() const;
};

}  // namespace hoilcd
