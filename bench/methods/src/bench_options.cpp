#include "hoilcd/bench/methods/bench_options.h"

#include "hoilcd/bench/methods/method_params.h"
#include "hoilcd/bench/methods/methods.h"
#include "hoilcd/core/util/error.h"

namespace hoilcd {

std::string BenchOptions::Check() const {
  for (const std::string& m : methods) {
    if (!IsMethod(m)) return "unknown method '" + m + "'";
  }
  for (const std::string& problem :
       {protocol.Check(), match.Check(), ransac.Check(), keypoints.Check(), detector.Check(),
        tracker.Check(), hoi.Check(), track_aware.Check(), thumbnail.Check(), sequence.Check(),
        temporal.Check(), tracking_metrics.Check(), slam_options.Check()}) {
    if (!problem.empty()) return problem;
  }
  try {
    CheckParams(params, methods);
  } catch (const InputError& e) {
    return e.problems().front().message;
  }
  if (lo_refits < 1) return "lo_refits must be positive";
  if (rrf_k < 0) return "rrf_k must be non-negative";
  if (threads < 0) return "threads must be 0 (every core) or positive";
  return "";
}

}  // namespace hoilcd
