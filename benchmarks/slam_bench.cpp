// The SLAM back end's cost for a full paper_room-sized run: 2000 frames (two 7 x 3 m laps), the
// laps protocol's ~1000 queries, and 8 methods (the default list's size), each run through
// RunSlam: 3 back ends at the operating point plus a 6-point ATE curve, and the oracle: 75 solves.
// Scores are synthetic (keyed RNG): the true match scores high with probability 0.5, so each
// method accepts a realistic mix of true and false loops. Compare the time with `hoilcd run`'s
// (docs/performance.md): the issue asks for <= 10 %.
#include <cmath>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "hoilcd/bench/slam/slam_run.h"
#include "hoilcd/core/util/random.h"

namespace hoilcd {
namespace {

constexpr int kFrames = 2000;
constexpr int kMethods = 8;

// Two clockwise laps of a 6 x 2 m rounded rectangle; odometry turns 0.01 rad/m too much.
std::vector<PoseRecord> Laps() {
  std::vector<PoseRecord> poses;
  const double perimeter = 2 * (6 + 2);
  Pose2d odo;
  Pose2d previous;
  for (int i = 0; i < kFrames; ++i) {
    const double s = std::fmod(2.0 * perimeter * i / kFrames, perimeter);
    Pose2d t;
    if (s < 6)
      t = {0.5 + s, 2.5, 0};
    else if (s < 8)
      t = {6.5, 2.5 - (s - 6), -M_PI / 2};
    else if (s < 14)
      t = {6.5 - (s - 8), 0.5, M_PI};
    else
      t = {0.5, 0.5 + (s - 14), M_PI / 2};
    if (i == 0) {
      odo = t;
    } else {
      Pose2d d = Between(previous, t);
      d.theta_rad += 0.01 * std::hypot(d.x_m, d.y_m);
      odo = Compose(odo, d);
    }
    previous = t;
    PoseRecord p;
    p.frame = i;
    p.time_s = i / 25.0;
    p.x_m = t.x_m, p.y_m = t.y_m, p.theta_rad = t.theta_rad;
    p.odo_x_m = odo.x_m, p.odo_y_m = odo.y_m, p.odo_theta_rad = odo.theta_rad;
    poses.push_back(p);
  }
  return poses;
}

void BM_RunSlam2000Frames8Methods(benchmark::State& state) {
  const std::vector<PoseRecord> poses = Laps();
  const std::vector<Query> queries = BuildQueries(poses, ProtocolOptions{});
  std::vector<std::vector<std::vector<double>>> scores(kMethods);
  for (int m = 0; m < kMethods; ++m) {
    for (const Query& q : queries) {
      Rng rng = KeyedRng(1, "bench.slam", m * kFrames + q.frame);
      std::vector<double> s(q.database.size());
      const bool hit = rng.Uniform() < 0.5;
      for (size_t j = 0; j < s.size(); ++j) s[j] = (hit && q.is_true_match[j] ? 30 : 0) + 25 * rng.Uniform();
      scores[m].push_back(s);
    }
  }
  std::vector<NamedScores> named;
  std::vector<std::string> names;
  for (int m = 0; m < kMethods; ++m) names.push_back("method" + std::to_string(m));
  for (int m = 0; m < kMethods; ++m) named.push_back({names[m], &scores[m]});
  const std::string scene =
      R"({"robot": {"wheelbase_m": 0.5}, "odometry": {"enabled": true, "error_scale": 1,
          "wheel_radius_error_frac": 0.001, "steer_offset_deg": 0.01, "wheelbase_error_frac": 0.002,
          "slip_per_accel_s2_m": 0.01, "turn_slip_per_lat_accel_s2_m": 0.01, "heading_noise_deg_sqrt_m": 0.03}})";
  SlamRunOptions options;
  int loops = 0;
  for (auto _ : state) {
    const SlamResult r = RunSlam(poses, scene, "scene.json", 25, 0.2, queries, named, options);
    loops = static_cast<int>(r.methods.front().loops.size());
    benchmark::DoNotOptimize(r.methods.back().backends.back().ate_rmse_m);
  }
  state.counters["queries"] = static_cast<double>(queries.size());
  state.counters["loops_method0"] = loops;
}
// One graph solve per back end with the oracle's loops: iterations and time per solve.
void BM_OneSolve(benchmark::State& state) {
  const std::vector<PoseRecord> poses = Laps();
  const std::vector<Query> queries = BuildQueries(poses, ProtocolOptions{});
  OdometryNoise noise;
  SlamOptions options;
  const PoseGraph graph = BuildPoseGraph(poses, OracleLoops(queries, poses, 0.2), noise, options);
  PoseGraphOptions o;
  o.backend = PoseGraphBackends()[state.range(0)];
  int iterations = 0;
  for (auto _ : state) iterations = OptimisePoseGraph(graph, o).iterations;
  state.SetLabel(o.backend);
  state.counters["iterations"] = iterations;
  state.counters["loops"] = static_cast<double>(graph.loops.size());
}
BENCHMARK(BM_OneSolve)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);

BENCHMARK(BM_RunSlam2000Frames8Methods)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace
}  // namespace hoilcd

BENCHMARK_MAIN();
