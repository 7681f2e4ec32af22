#include "hoilcd/bench/slam/slam.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include <gtest/gtest.h>

#include "hoilcd/core/util/error.h"
#include "option_properties.h"

namespace hoilcd {
namespace {

constexpr double kRadiusM = 0.2;

// `laps` counter-clockwise laps of a 1.2 m circle at 0.05 m per frame, 0.2 s per frame; the
// odometry over-reads distance by 1 % and turns 0.05 rad/m too much, so it drifts.
std::vector<PoseRecord> DriftingLaps(int laps) {
  const double radius = 1.2, step = 0.05;
  const int per_lap = static_cast<int>(std::round(2 * M_PI * radius / step));
  std::vector<PoseRecord> poses;
  Pose2d odo;
  Pose2d previous;
  for (int i = 0; i < laps * per_lap; ++i) {
    const double a = 2 * M_PI * i / per_lap;
    const Pose2d truth{radius * std::cos(a), radius * std::sin(a), std::remainder(a + M_PI / 2, 2 * M_PI)};
    if (i == 0) {
      odo = truth;
    } else {
      Pose2d d = Between(previous, truth);
      const double length = std::hypot(d.x_m, d.y_m);
      d.x_m *= 1.01, d.y_m *= 1.01, d.theta_rad += 0.05 * length;
      odo = Compose(odo, d);
    }
    previous = truth;
    PoseRecord p;
    p.frame = i;
    p.time_s = 0.2 * i;
    p.x_m = truth.x_m, p.y_m = truth.y_m, p.theta_rad = truth.theta_rad;
    p.odo_x_m = odo.x_m, p.odo_y_m = odo.y_m, p.odo_theta_rad = odo.theta_rad;
    poses.push_back(p);
  }
  return poses;
}

OdometryNoise DriftNoise() {
  OdometryNoise n;
  n.distance_sd_frac = 0.01;
  n.heading_sd_rad_per_m = 0.05;
  n.heading_var_rad2_per_m = 0;
  return n;
}

std::vector<Query> LapQueries(const std::vector<PoseRecord>& poses) {
  ProtocolOptions protocol;
  protocol.radius_m = kRadiusM;
  protocol.ground_truth = "true";  // label queries as the loops are judged: by true positions
  return BuildQueries(poses, protocol);
}

// One score per (query, database entry): score(query, index into its database).
template <typename ScoreFn>
std::vector<std::vector<double>> ScoreEach(const std::vector<Query>& queries, ScoreFn score) {
  std::vector<std::vector<double>> scores;
  for (const Query& q : queries) {
    std::vector<double> row(q.database.size());
    for (size_t j = 0; j < q.database.size(); ++j) row[j] = score(q, j);
    scores.push_back(std::move(row));
  }
  return scores;
}

TEST(SlamTest, OracleLoopsHalveTheOdometryAteOnADriftingSequenceWithAndWithoutKeyframes) {
  const auto poses = DriftingLaps(2);
  const auto queries = LapQueries(poses);
  const auto oracle = OracleLoops(queries, poses, kRadiusM);
  ASSERT_GT(oracle.size(), 50u);
  SlamOptions options;
  const SlamScore odometry = ScoreOdometry(poses, options);
  ASSERT_GT(odometry.ate_rmse_m, 0.1);  // it really drifts
  for (const int every : {1, 5})
    for (const std::string& backend : PoseGraphBackends()) {
      options.keyframe_every = every;
      const SlamScore s = SolveSlam(poses, oracle, DriftNoise(), options, backend);
      EXPECT_LE(s.ate_rmse_m, 0.5 * odometry.ate_rmse_m) << backend;
      EXPECT_LT(s.rpe_rmse_m, odometry.rpe_rmse_m) << backend;
      EXPECT_EQ(s.false_loops, 0);
      EXPECT_EQ(s.loops_accepted, static_cast<int>(oracle.size()));
    }
}

TEST(SlamTest, OneFalseLoopWrecksPlainLeastSquaresButNotTheRobustBackEnd) {
  // A method at a strict threshold accepts few loops: every 30th query's true loop.
  const auto poses = DriftingLaps(2);
  const int per_lap = static_cast<int>(poses.size()) / 2;
  const auto queries = LapQueries(poses);
  const auto all = OracleLoops(queries, poses, kRadiusM);
  std::vector<LoopClosure> loops;
  for (size_t i = 0; i < all.size(); i += 30) loops.push_back(all[i]);
  ASSERT_GE(loops.size(), 4u);
  const SlamOptions options;
  const SlamScore odometry = ScoreOdometry(poses, options);
  std::map<std::string, SlamScore> oracle;
  for (const std::string& b : PoseGraphBackends()) oracle[b] = SolveSlam(poses, loops, DriftNoise(), options, b);
  // Query in lap 2 matched to the far side of the circle in lap 1 (2.4 m away).
  const int query = per_lap + 3 * per_lap / 4, reference = per_lap / 4;
  loops.push_back({query, reference, 99.0, BaseDistanceM(poses[query], poses[reference]) <= kRadiusM});
  ASSERT_FALSE(loops.back().is_true);
  const SlamScore plain = SolveSlam(poses, loops, DriftNoise(), options, "plain");
  EXPECT_EQ(plain.false_loops, 1);
  const double drift_removed = odometry.ate_rmse_m - oracle["plain"].ate_rmse_m;
  ASSERT_GT(drift_removed, 0);
  EXPECT_GT(plain.ate_rmse_m - oracle["plain"].ate_rmse_m, drift_removed);
  const SlamScore dcs = SolveSlam(poses, loops, DriftNoise(), options, "dcs");
  EXPECT_LE(dcs.ate_rmse_m, 1.1 * oracle["plain"].ate_rmse_m);
  EXPECT_LE(dcs.ate_rmse_m, 1.1 * oracle["dcs"].ate_rmse_m);
  const SlamScore cauchy = SolveSlam(poses, loops, DriftNoise(), options, "cauchy");
  std::printf("odometry %.4f oracle plain %.4f cauchy %.4f dcs %.4f; with false loop plain %.4f cauchy %.4f dcs %.4f\n",
              odometry.ate_rmse_m, oracle["plain"].ate_rmse_m, oracle["cauchy"].ate_rmse_m, oracle["dcs"].ate_rmse_m,
              plain.ate_rmse_m, cauchy.ate_rmse_m, dcs.ate_rmse_m);
}

TEST(SlamTest, AcceptLoopsTakesTopOneAboveTheThresholdAndJudgesItByTruePosition) {
  const auto poses = DriftingLaps(2);
  const auto queries = LapQueries(poses);
  // True match scores 10 on even queries; on odd ones a false frame scores 5.
  const auto scores = ScoreEach(queries, [&](const Query& q, size_t j) {
    const bool near = BaseDistanceM(poses[q.frame], poses[q.database[j]]) <= kRadiusM;
    if (q.frame % 2 == 0 && near) return 10.0;
    if (q.frame % 2 == 1 && !near && j == 0) return 5.0;
    return 0.0;
  });
  const auto all = AcceptLoops(queries, scores, 0.0, poses, kRadiusM);
  const auto strict = AcceptLoops(queries, scores, 6.0, poses, kRadiusM);
  ASSERT_FALSE(strict.empty());
  for (const LoopClosure& l : strict) {
    EXPECT_TRUE(l.is_true);
    EXPECT_EQ(l.score, 10);
  }
  EXPECT_GT(all.size(), strict.size());
  EXPECT_EQ(ThresholdAtFullPrecision(queries, scores, poses, kRadiusM), 10.0);
  EXPECT_TRUE(AcceptLoops(queries, scores, 11.0, poses, kRadiusM).empty());
  const auto candidates = ThresholdCandidates(queries, scores, 10);
  EXPECT_EQ(candidates.front(), 0.0);  // queries whose every score is 0
  EXPECT_EQ(candidates.back(), 10.0);
}

TEST(SlamTest, FullPrecisionThresholdIsNaNWhenTheBestMatchIsFalse) {
  const auto poses = DriftingLaps(2);
  const auto queries = LapQueries(poses);
  const auto scores = ScoreEach(queries, [&](const Query& q, size_t j) {
    return BaseDistanceM(poses[q.frame], poses[q.database[j]]) > 1.0 ? 1.0 : 0.0;
  });
  EXPECT_TRUE(std::isnan(ThresholdAtFullPrecision(queries, scores, poses, kRadiusM)));
}

// Frames 0..n-1 of recording runs of the given lengths (only frame and run are set).
std::vector<PoseRecord> Frames(const std::vector<int>& run_lengths) {
  std::vector<PoseRecord> poses;
  for (size_t r = 0; r < run_lengths.size(); ++r) {
    for (int i = 0; i < run_lengths[r]; ++i) {
      PoseRecord p;
      p.frame = static_cast<int>(poses.size());
      p.run = static_cast<int>(r);
      poses.push_back(p);
    }
  }
  return poses;
}

// Two recording runs of a lap each from the same dock an hour apart: run 0's odometry is exact, run
// 1's drifts (DriftingLaps) from the dock, where it restarted.
std::vector<PoseRecord> TwoRuns() {
  std::vector<PoseRecord> poses = DriftingLaps(1);
  for (PoseRecord& p : poses) p.odo_x_m = p.x_m, p.odo_y_m = p.y_m, p.odo_theta_rad = p.theta_rad;
  const int first = static_cast<int>(poses.size());
  for (PoseRecord p : DriftingLaps(1)) {
    p.frame += first;
    p.time_s += 3600;
    p.run = 1;
    poses.push_back(p);
  }
  return poses;
}

TEST(SlamTest, EachRunsFirstAndLastFramesAreKeyframesAndNoOdometryEdgeJoinsTwoRuns) {
  EXPECT_EQ(Keyframes(Frames({11, 7}), 5), (std::vector<int>{0, 5, 10, 11, 16, 17}));
  const std::vector<PoseRecord> poses = TwoRuns();
  const int second = static_cast<int>(poses.size()) / 2;  // run 1's first frame
  const SlamOptions options;
  const PoseGraph graph = BuildPoseGraph(poses, {}, DriftNoise(), options);
  const std::vector<int> keyframes = Keyframes(poses, options.keyframe_every);
  const int second_node = static_cast<int>(std::find(keyframes.begin(), keyframes.end(), second) - keyframes.begin());
  ASSERT_LT(second_node, static_cast<int>(keyframes.size()));
  EXPECT_EQ(keyframes[second_node - 1], second - 1);           // run 0's last frame
  EXPECT_EQ(graph.fixed, (std::vector<int>{0, second_node}));  // each run starts at the known dock
  EXPECT_EQ(graph.odometry.size(), graph.nodes.size() - 2);
  for (const PoseEdge& e : graph.odometry) EXPECT_NE(e.to, second_node);
  // Each frame's pose comes from a keyframe of its own run: moving run 1's nodes moves its frames
  // alone.
  std::vector<Pose2d> moved = graph.nodes;
  for (size_t k = second_node; k < moved.size(); ++k) moved[k].x_m += 1;
  const std::vector<Pose2d> frames = FramePosesFromKeyframes(poses, moved, options.keyframe_every);
  for (size_t f = 0; f < poses.size(); ++f) {
    EXPECT_NEAR(frames[f].x_m, poses[f].odo_x_m + (poses[f].run == 1 ? 1 : 0), 1e-9) << f;
    EXPECT_NEAR(frames[f].y_m, poses[f].odo_y_m, 1e-9) << f;
  }
}

TEST(SlamTest, LoopsFromALaterRunToTheFirstPullTheLaterRunsDriftOut) {
  const std::vector<PoseRecord> poses = TwoRuns();
  ProtocolOptions protocol;
  protocol.protocol = "runs";
  protocol.ground_truth = "true";
  const std::vector<LoopClosure> oracle = OracleLoops(BuildQueries(poses, protocol), poses, kRadiusM);
  ASSERT_GT(oracle.size(), 100u);
  for (const LoopClosure& l : oracle) ASSERT_EQ(poses[l.query].run, 1);
  const SlamOptions options;
  const SlamScore odometry = ScoreOdometry(poses, options);
  ASSERT_GT(odometry.ate_rmse_m, 0.05);  // run 1 drifts
  for (const std::string& backend : PoseGraphBackends()) {
    const SlamScore s = SolveSlam(poses, oracle, DriftNoise(), options, backend);
    EXPECT_LE(s.ate_rmse_m, 0.5 * odometry.ate_rmse_m) << backend;
    EXPECT_LT(s.rpe_rmse_m, odometry.rpe_rmse_m) << backend;
    // Both runs start at the dock, where they were anchored.
    for (const size_t first : {size_t{0}, poses.size() / 2}) {
      EXPECT_NEAR(s.poses[first].x_m, poses[first].x_m, 1e-12) << backend;
      EXPECT_NEAR(s.poses[first].y_m, poses[first].y_m, 1e-12) << backend;
    }
  }
}

TEST(SlamTest, KeyframesCoverEveryFrameAndFramePosesFollowTheOdometry) {
  EXPECT_EQ(Keyframes(Frames({11}), 5), (std::vector<int>{0, 5, 10}));
  EXPECT_EQ(Keyframes(Frames({12}), 5), (std::vector<int>{0, 5, 10, 11}));
  const auto poses = DriftingLaps(1);
  const SlamOptions options;
  const PoseGraph graph = BuildPoseGraph(poses, {}, DriftNoise(), options);
  const std::vector<Pose2d> frames = FramePosesFromKeyframes(poses, graph.nodes, options.keyframe_every);
  const std::vector<Pose2d> odometry = OdometryPoses(poses);
  ASSERT_EQ(frames.size(), poses.size());
  for (size_t f = 0; f < frames.size(); ++f) {
    EXPECT_NEAR(frames[f].x_m, odometry[f].x_m, 1e-9);
    EXPECT_NEAR(frames[f].y_m, odometry[f].y_m, 1e-9);
  }
}

TEST(SlamTest, NoLoopLeavesTheOdometry) {
  const auto poses = DriftingLaps(2);
  const SlamOptions options;
  const SlamScore s = SolveSlam(poses, {}, DriftNoise(), options, "dcs");
  EXPECT_EQ(s.ate_rmse_m, ScoreOdometry(poses, options).ate_rmse_m);
  EXPECT_EQ(s.loops_accepted, 0);
}

std::string NoiseError(const std::string& json) {
  try {
    OdometryNoise::FromSceneJson(json, "scene.json", 25);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SlamTest, OdometryNoiseIsReadFromEitherSceneOdometryModel) {
  const OdometryNoise a = OdometryNoise::FromSceneJson(
      R"({"robot": {"wheelbase_m": 0.5, "integration_rate_hz": 100},
          "odometry": {"enabled": true, "encoder_noise_frac": 0.02, "steer_noise_deg": 0.2,
                       "steer_bias_deg": 0.0, "slip_frac": 0.0}})",
      "scene.json", 25);
  EXPECT_NEAR(a.distance_sd_frac, 0.01, 1e-12);  // 4 steps per frame: 0.02 / √4
  EXPECT_NEAR(a.heading_sd_rad_per_m, 0.2 * M_PI / 180 / 2 / 0.5, 1e-12);
  const OdometryNoise b = OdometryNoise::FromSceneJson(
      R"({"robot": {"wheelbase_m": 0.5},
          "odometry": {"enabled": true, "error_scale": 2, "wheel_radius_error_frac": 0.001,
                       "steer_offset_deg": 0, "wheelbase_error_frac": 0, "slip_per_accel_s2_m": 0,
                       "turn_slip_per_lat_accel_s2_m": 0, "heading_noise_deg_sqrt_m": 0.03}})",
      "scene.json", 25);
  EXPECT_NEAR(b.distance_sd_frac, 0.002, 1e-12);
  EXPECT_NEAR(b.heading_var_rad2_per_m, std::pow(0.06 * M_PI / 180, 2), 1e-15);
  const OdometryNoise off = OdometryNoise::FromSceneJson(R"({"odometry": {"enabled": false}})", "scene.json", 25);
  EXPECT_EQ(off.distance_sd_frac, 0);
  const Eigen::Matrix3d info = off.Information(Pose2d{0.1, 0, 0});
  EXPECT_TRUE(info.allFinite());
  EXPECT_GT(info(0, 0), 0);
}

TEST(SlamTest, SceneWithoutAnOdometryModelIsAClearError) {
  EXPECT_NE(NoiseError("not json").find("expected the resolved scene"), std::string::npos);
  EXPECT_NE(NoiseError(R"({"robot": {}})").find("scene.json: /odometry"), std::string::npos);
  EXPECT_NE(NoiseError(R"({"odometry": {"enabled": true, "wobble": 1}})").find("encoder_noise_frac or"),
            std::string::npos);
  EXPECT_NE(NoiseError(R"({"odometry": {"encoder_noise_frac": 0.01}})").find("scene.json: /robot/wheelbase_m"),
            std::string::npos);
}

TEST(SlamTest, BadSlamOptionsAreRejected) {
  SlamOptions o;
  o.loop_sd_m = 0;
  EXPECT_NE(o.Check().find("loop_sd_m"), std::string::npos);
  o = SlamOptions{};
  o.loop_yaw_sd_deg = -1;
  EXPECT_NE(o.Check().find("loop_yaw_sd_deg"), std::string::npos);
  o = SlamOptions{};
  o.rpe_delta_m = 0;
  EXPECT_NE(o.Check().find("rpe_delta_m"), std::string::npos);
  o = SlamOptions{};
  o.keyframe_every = 0;
  EXPECT_NE(o.Check().find("keyframe_every"), std::string::npos);
  o = SlamOptions{};
  o.loop_threshold = INFINITY;
  EXPECT_EQ(o.Check(), "loop_threshold: must be a finite number or NaN (got inf)");
  o = SlamOptions{};
  o.graph.dcs_phi = 0;
  EXPECT_EQ(o.Check(), "graph/dcs_phi: must be above 0 (got 0)");
}

TEST(SlamTest, OptionsHoldTheirTablesDefaultsWithNoLoopThresholdAndEveryBoundIsChecked) {
  EXPECT_TRUE(std::isnan(SlamOptions().loop_threshold));  // NaN: the operating point
  ExpectConstructedHoldsTheTableDefaults<SlamOptions>();
  EXPECT_EQ(ExpectEveryBoundCrossedIsNamedByCheck<SlamOptions>(), 9);
}

}  // namespace
}  // namespace hoilcd
