// The SLAM consequence over a whole bench run: odometry alone, the oracle and every method's
// accepted loops, each optimised under every back end (slam.h), plus an ATE-vs-threshold curve per
// method under the headline back end. The loop threshold of each method is, in order of
// preference: --loop-threshold, the 100 %-precision threshold of a calibration sequence rendered
// with another seed, or (said so in the report) that of the test sequence itself.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "hoilcd/bench/slam/slam.h"
#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

// Defaults and ranges: Table() in slam_run.cpp.
struct SlamRunOptions {
  SlamOptions slam;  // back end, loop model, --loop-threshold
  int curve_points;  // thresholds on each ATE curve (count)
  int threads;       // methods solved at once (0: every core)
  // Not an option but a result passed in (so not in the table; empty when constructed): method ->
  // threshold at 100 % precision on the calibration run.
  std::map<std::string, double> calibrated_threshold;

  SlamRunOptions();  // the registered defaults
  // Every field once: name, default, unit, range, description.
  static const OptionTable<SlamRunOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

struct MethodSlam {
  std::string method;
  double threshold = 0;                              // NaN: no threshold gives a true top-1 (no loop accepted)
  std::string threshold_source;                      // "--loop-threshold" | "calibration" | "test sequence"
  std::vector<LoopClosure> loops;                    // accepted at `threshold`
  std::vector<SlamScore> backends;                   // one per PoseGraphBackends(), same order
  std::vector<double> curve_threshold, curve_ate_m;  // ATE vs threshold, headline back end
  std::vector<int> curve_loops;                      // loops accepted at each curve threshold
  const SlamScore& Headline(const std::string& backend) const;
};

struct SlamResult {
  std::string backend;  // headline back end
  OdometryNoise noise;
  SlamScore odometry;
  std::vector<LoopClosure> oracle_loops;
  std::vector<SlamScore> oracle;  // one per PoseGraphBackends()
  std::vector<MethodSlam> methods;
  std::vector<std::string> notes;  // what a reader must know (no loop accepted, threshold source)
  double seconds = 0;              // wall time of RunSlam
};

// A method's per-query scores (parallel to the queries), by name.
struct NamedScores {
  std::string name;
  const std::vector<std::vector<double>>* scores = nullptr;
};

// InputError when the scene has no odometry model or a graph cannot be solved.
SlamResult RunSlam(const std::vector<PoseRecord>& poses, const std::string& scene_json, const std::string& scene_path,
                   double frame_rate_hz, double radius_m, const std::vector<Query>& queries,
                   const std::vector<NamedScores>& methods, const SlamRunOptions& options);

}  // namespace hoilcd
