#include "hoilcd/bench/slam/slam_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/parallel.h"

namespace hoilcd {

SlamRunOptions::SlamRunOptions() { Table().FillDefaults(this); }

const OptionTable<SlamRunOptions>& SlamRunOptions::Table() {
  using O = SlamRunOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Nest("slam", &O::slam, SlamOptions::Table())
          .Add("curve_points", &O::curve_points, 6, "", R::Closed(2, 1000), "thresholds on each ATE curve")
          .Add("threads", &O::threads, 0, "", R::Any().AtLeast(0), "methods solved at once (0: every core)");
  return table;
}

std::string SlamRunOptions::Check() const { return Table().FirstProblem(*this); }

const SlamScore& MethodSlam::Headline(const std::string& backend) const {
  const auto it =
      std::find_if(backends.begin(), backends.end(), [&](const SlamScore& s) { return s.backend == backend; });
  HOILCD_CHECK_MSG(it != backends.end(), "no back end " + backend);
  return *it;
}

SlamResult RunSlam(const std::vector<PoseRecord>& poses, const std::string& scene_json, const std::string& scene_path,
                   double frame_rate_hz, double radius_m, const std::vector<Query>& queries,
                   const std::vector<NamedScores>& methods, const SlamRunOptions& options) {
  if (const std::string p = options.Check(); !p.empty()) throw InputError("slam", p);
  const auto start = std::chrono::steady_clock::now();
  const SlamOptions& slam = options.slam;
  SlamResult out;
  out.backend = slam.graph.backend;
  out.noise = OdometryNoise::FromSceneJson(scene_json, scene_path, frame_rate_hz);
  out.odometry = ScoreOdometry(poses, slam);
  out.oracle_loops = OracleLoops(queries, poses, radius_m);
  if (out.oracle_loops.empty()) out.notes.push_back("the sequence has no true loop: the oracle is the odometry");
  for (const std::string& b : PoseGraphBackends())
    out.oracle.push_back(SolveSlam(poses, out.oracle_loops, out.noise, slam, b));

  // Each method's graphs are independent (one single-threaded Ceres solve each): methods run in
  // parallel, each writing only its own slot, so the result does not depend on the thread count.
  out.methods.resize(methods.size());
  std::vector<std::string> method_notes(methods.size());
  ParallelFor(static_cast<int64_t>(methods.size()), options.threads, [&](int64_t i) {
    const NamedScores& m = methods[static_cast<size_t>(i)];
    MethodSlam& ms = out.methods[static_cast<size_t>(i)];
    ms.method = m.name;
    if (!std::isnan(slam.loop_threshold)) {
      ms.threshold = slam.loop_threshold, ms.threshold_source = "--loop-threshold";
    } else if (auto it = options.calibrated_threshold.find(m.name); it != options.calibrated_threshold.end()) {
      ms.threshold = it->second, ms.threshold_source = "calibration";
    } else {
      ms.threshold = ThresholdAtFullPrecision(queries, *m.scores, poses, radius_m);
      ms.threshold_source = "test sequence";
    }
    if (!std::isnan(ms.threshold)) ms.loops = AcceptLoops(queries, *m.scores, ms.threshold, poses, radius_m);
    if (ms.loops.empty()) {
      char text[200];
      std::snprintf(text, sizeof(text), "%s: threshold %g (%s) accepts no loop; its trajectory is the odometry",
                    m.name.c_str(), ms.threshold, ms.threshold_source.c_str());
      method_notes[static_cast<size_t>(i)] = text;
    }
    for (const std::string& b : PoseGraphBackends())
      ms.backends.push_back(SolveSlam(poses, ms.loops, out.noise, slam, b));
    for (double t : ThresholdCandidates(queries, *m.scores, options.curve_points)) {
      const std::vector<LoopClosure> loops = AcceptLoops(queries, *m.scores, t, poses, radius_m);
      ms.curve_threshold.push_back(t);
      ms.curve_loops.push_back(static_cast<int>(loops.size()));
      ms.curve_ate_m.push_back(SolveSlam(poses, loops, out.noise, slam, out.backend).ate_rmse_m);
    }
  });
  for (const std::string& note : method_notes)
    if (!note.empty()) out.notes.push_back(note);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace hoilcd
