#include "hoilcd/bench/evaluation/protocol.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <gtest/gtest.h>

#include "option_properties.h"

namespace hoilcd {
namespace {

constexpr int kFramesPerLap = 100;

// `laps` laps of a 1 m circle at 1 frame per second; clockwise: heading = angle - π/2, so the
// heading turns by -2π per lap. Frame k and k + 100 are at the same place; neighbouring frames are
// 2 sin(π/100) ≈ 0.0628 m apart, so frames within 3 steps are within 0.2 m (0.188 m), 4 are not.
std::vector<PoseRecord> CirclePoses(int laps, bool clockwise = true) {
  std::vector<PoseRecord> poses;
  const double sign = clockwise ? -1.0 : 1.0;
  for (int i = 0; i < laps * kFramesPerLap; ++i) {
    const double angle = sign * 2.0 * M_PI * i / kFramesPerLap;
    PoseRecord p;
    p.frame = i;
    p.time_s = i;
    p.x_m = 3.0 + std::cos(angle);
    p.y_m = 1.5 + std::sin(angle);
    p.theta_rad = std::remainder(angle + sign * M_PI / 2, 2 * M_PI);
    p.odo_x_m = p.x_m;  // perfect odometry unless a test says otherwise
    p.odo_y_m = p.y_m;
    p.odo_theta_rad = p.theta_rad;
    poses.push_back(p);
  }
  return poses;
}

std::vector<int> TrueFrames(const Query& q) {
  std::vector<int> out;
  for (size_t i = 0; i < q.database.size(); ++i) {
    if (q.is_true_match[i]) out.push_back(q.database[i]);
  }
  return out;
}

TEST(LapIndexFromPoses, CountsOneLapPerFullTurnInEitherDirection) {
  for (bool clockwise : {true, false}) {
    const std::vector<int> laps = LapIndexFromPoses(CirclePoses(3, clockwise));
    ASSERT_EQ(laps.size(), 300u);
    EXPECT_EQ(laps[0], 0);
    EXPECT_EQ(laps[99], 0);
    EXPECT_EQ(laps[100], 1);
    EXPECT_EQ(laps[199], 1);
    EXPECT_EQ(laps[200], 2);
    EXPECT_EQ(laps[299], 2);
  }
}

// Two recording runs of the circle: run 0 drives 1.25 laps (125 frames, ending a quarter lap past
// the dock), run 1 starts at the dock again an hour later and drives `laps_1` laps. At run 1's first
// frame the heading jumps back to the dock's.
std::vector<PoseRecord> TwoRuns(double laps_1 = 1) {
  std::vector<PoseRecord> poses = CirclePoses(2);
  poses.resize(125);
  std::vector<PoseRecord> second = CirclePoses(2);
  second.resize(static_cast<size_t>(laps_1 * kFramesPerLap));
  for (PoseRecord& p : second) {
    p.frame += 125;
    p.time_s += 3600;
    p.run = 1;
    poses.push_back(p);
  }
  return poses;
}

TEST(LapIndexFromPoses, EachRunUnwrapsItsHeadingFromTheDockAndCountsLapsOnFromTheRunBefore) {
  const std::vector<int> laps = LapIndexFromPoses(TwoRuns(2));
  ASSERT_EQ(laps.size(), 325u);
  EXPECT_EQ(laps[99], 0);
  EXPECT_EQ(laps[100], 1);
  EXPECT_EQ(laps[124], 1);  // run 0's second lap, a quarter of it driven
  EXPECT_EQ(laps[125], 2);  // run 1 starts a lap of its own at the dock
  EXPECT_EQ(laps[224], 2);
  EXPECT_EQ(laps[225], 3);
  EXPECT_EQ(laps[324], 3);
  EXPECT_TRUE(std::is_sorted(laps.begin(), laps.end()));
  // Unwrapped through the jump, run 1 would have been in run 0's second lap for three quarters of a lap.
  std::vector<PoseRecord> one_run = TwoRuns(2);
  for (PoseRecord& p : one_run) p.run = 0;
  EXPECT_EQ(LapIndexFromPoses(one_run)[200], 1);
}

TEST(BuildQueries, RunsProtocolQueriesEveryLaterRunFrameAgainstTheWholeFirstRun) {
  ProtocolOptions options;
  options.protocol = "runs";
  const std::vector<PoseRecord> poses = TwoRuns();
  const std::vector<Query> queries = BuildQueries(poses, options);
  ASSERT_EQ(queries.size(), 100u);
  std::vector<int> first_run(125);
  std::iota(first_run.begin(), first_run.end(), 0);
  for (const Query& q : queries) {
    EXPECT_EQ(q.run, 1);
    EXPECT_EQ(q.lap, 2);
    EXPECT_EQ(q.database, first_run) << q.frame;
  }
  // Run 1's frame 10 is where run 0 was at frames 10 and 110.
  EXPECT_EQ(queries[10].frame, 135);
  EXPECT_EQ(TrueFrames(queries[10]), (std::vector<int>{7, 8, 9, 10, 11, 12, 13, 107, 108, 109, 110, 111, 112, 113}));
  // laps: run 0's first lap is the database of run 0's second lap and of every run-1 frame.
  const std::vector<Query> laps = BuildQueries(poses, ProtocolOptions());
  ASSERT_EQ(laps.size(), 125u);
  EXPECT_EQ(laps.front().frame, 100);
  EXPECT_EQ(laps.front().run, 0);
  EXPECT_EQ(laps.back().run, 1);
  EXPECT_EQ(laps.back().database.back(), 99);
}

TEST(ProtocolOptions, CheckNamesWhatIsWrong) {
  ProtocolOptions options;
  EXPECT_EQ(options.Check(), "");
  options.protocol = "lap";
  EXPECT_EQ(options.Check(), "protocol: must be one of: laps, revisit, runs (got 'lap')");
  options = ProtocolOptions();
  options.radius_m = 0;
  EXPECT_NE(options.Check().find("radius_m"), std::string::npos);
  options = ProtocolOptions();
  options.exclusion_window_s = -1;
  EXPECT_NE(options.Check().find("exclusion_window_s"), std::string::npos);
  options = ProtocolOptions();
  options.heading_tolerance_deg = 200;
  EXPECT_NE(options.Check().find("heading_tolerance_deg"), std::string::npos);
}

TEST(ProtocolOptions, HoldThePapersDefaultsFromTheirTableAndEveryBoundIsChecked) {
  const ProtocolOptions options;
  EXPECT_EQ(options.protocol, "laps");
  EXPECT_EQ(options.radius_m, 0.2);  // paper, section 5.1
  EXPECT_EQ(options.exclusion_window_s, 10);
  EXPECT_EQ(options.ground_truth, "odometry");
  EXPECT_EQ(options.overlap_threshold, 0.5);
  ExpectConstructedHoldsTheTableDefaults<ProtocolOptions>();
  // radius, heading tolerance, exclusion window; overlap threshold, stride and depth tolerance
  // (each bounded at both ends).
  EXPECT_EQ(ExpectEveryBoundCrossedIsNamedByCheck<ProtocolOptions>(), 9);
}

TEST(BuildQueries, LapsUsesFirstLapAsDatabaseAndLaterLapsAsQueries) {
  const std::vector<Query> queries = BuildQueries(CirclePoses(2), ProtocolOptions());
  ASSERT_EQ(queries.size(), 100u);
  EXPECT_EQ(queries.front().frame, 100);
  EXPECT_EQ(queries.back().frame, 199);
  const Query& q = queries[50];  // frame 150, far in time from every first-lap frame
  EXPECT_EQ(q.lap, 1);
  ASSERT_EQ(q.database.size(), 100u);
  EXPECT_EQ(q.database.front(), 0);
  EXPECT_EQ(q.database.back(), 99);
  EXPECT_EQ(TrueFrames(q), (std::vector<int>{47, 48, 49, 50, 51, 52, 53}));
}

TEST(BuildQueries, ExclusionWindowRemovesFramesNearInTime) {
  const std::vector<Query> queries = BuildQueries(CirclePoses(2), ProtocolOptions());
  const Query& q = queries[0];  // frame 100: frames 90..99 are within 10 s
  ASSERT_EQ(q.frame, 100);
  ASSERT_EQ(q.database.size(), 90u);
  EXPECT_EQ(q.database.back(), 89);
  // Without the window 97, 98, 99 would be true matches too.
  EXPECT_EQ(TrueFrames(q), (std::vector<int>{0, 1, 2, 3}));
  ProtocolOptions no_window;
  no_window.exclusion_window_s = 0;
  EXPECT_EQ(TrueFrames(BuildQueries(CirclePoses(2), no_window)[0]), (std::vector<int>{0, 1, 2, 3, 97, 98, 99}));
}

TEST(BuildQueries, RadiusAndHeadingToleranceDecideTrueMatches) {
  ProtocolOptions options;
  options.radius_m = 0.26;  // 4 steps = 0.251 m now count
  EXPECT_EQ(TrueFrames(BuildQueries(CirclePoses(2), options)[50]).size(), 9u);
  options.radius_m = 0.2;
  options.heading_tolerance_deg = 11;  // 3 steps turn 10.8°
  EXPECT_EQ(TrueFrames(BuildQueries(CirclePoses(2), options)[50]).size(), 7u);
  options.heading_tolerance_deg = 4;  // 1 step turns 3.6°
  EXPECT_EQ(TrueFrames(BuildQueries(CirclePoses(2), options)[50]), (std::vector<int>{49, 50, 51}));
}

TEST(IsTrueMatch, SamePlaceFacingTheOtherWayFailsOnlyWithAHeadingTolerance) {
  PoseRecord a, b;
  a.x_m = 1;
  b.x_m = 1.15;
  b.theta_rad = M_PI;
  ProtocolOptions options;
  EXPECT_TRUE(IsTrueMatch(a, b, options));
  options.heading_tolerance_deg = 90;
  EXPECT_FALSE(IsTrueMatch(a, b, options));
  b.theta_rad = -179.0 * M_PI / 180.0;
  a.theta_rad = 179.0 * M_PI / 180.0;  // 2° apart across the ±π seam
  options.heading_tolerance_deg = 3;
  EXPECT_TRUE(IsTrueMatch(a, b, options));
  b.x_m = 1.21;
  EXPECT_FALSE(IsTrueMatch(a, b, options));
}

TEST(BuildQueries, RevisitMakesEveryFrameAQueryAgainstOlderFramesOnly) {
  ProtocolOptions options;
  options.protocol = "revisit";
  const std::vector<Query> queries = BuildQueries(CirclePoses(2), options);
  ASSERT_EQ(queries.size(), 200u);
  EXPECT_TRUE(queries[5].database.empty());
  EXPECT_EQ(queries[5].NumTrueMatches(), 0);  // kept, to be counted as skipped
  const Query& q = queries[150];
  ASSERT_EQ(q.database.size(), 140u);  // frames 0..139: older than 10 s
  EXPECT_EQ(q.database.back(), 139);
  EXPECT_EQ(TrueFrames(q), (std::vector<int>{47, 48, 49, 50, 51, 52, 53}));
  EXPECT_EQ(queries[60].NumTrueMatches(), 0);  // first lap: nothing older is near
}

// Odometry that drifted 0.15 m along +x during the second lap: the odometric labels of a query
// then point at other first-lap frames than the true ones.
std::vector<PoseRecord> DriftedSecondLap() {
  std::vector<PoseRecord> poses = CirclePoses(2);
  for (PoseRecord& p : poses)
    if (p.frame >= kFramesPerLap) p.odo_x_m += 0.15;
  return poses;
}

TEST(GroundTruth, OdometryLabelsComeFromOdometricPositionsTrueLabelsFromTruePoses) {
  ProtocolOptions by_odometry, by_truth;
  by_truth.ground_truth = "true";
  const std::vector<PoseRecord> poses = DriftedSecondLap();
  EXPECT_EQ(TrueFrames(BuildQueries(poses, by_truth)[50]), (std::vector<int>{47, 48, 49, 50, 51, 52, 53}));
  // Frame 150 sits at angle -pi (x = 2, y = 1.5); its odometry says x = 2.15, closer to the
  // first-lap frames on either side of 50 whose x is larger.
  const std::vector<int> odometric = TrueFrames(BuildQueries(poses, by_odometry)[50]);
  EXPECT_NE(odometric, TrueFrames(BuildQueries(poses, by_truth)[50]));
  EXPECT_FALSE(odometric.empty());
  for (int f : odometric) {
    EXPECT_LE(std::hypot(poses[f].odo_x_m - poses[150].odo_x_m, poses[f].odo_y_m - poses[150].odo_y_m), 0.2);
  }
}

TEST(GroundTruth, RelabelKeepsQueriesAndDatabasesAndCompareCountsTheDifferences) {
  ProtocolOptions options;
  const std::vector<PoseRecord> poses = DriftedSecondLap();
  const std::vector<Query> by_odometry = BuildQueries(poses, options);
  const std::vector<Query> by_truth = RelabelQueries(by_odometry, poses, options, "true");
  ASSERT_EQ(by_truth.size(), by_odometry.size());
  for (size_t i = 0; i < by_truth.size(); ++i) {
    EXPECT_EQ(by_truth[i].frame, by_odometry[i].frame);
    EXPECT_EQ(by_truth[i].database, by_odometry[i].database);
  }
  const LabelDisagreement d = CompareLabels(by_odometry, by_truth);
  EXPECT_EQ(d.queries, 100);
  EXPECT_GT(d.queries_differing, 50);
  EXPECT_GT(d.pairs_differing, d.queries_differing);
  const LabelDisagreement same = CompareLabels(by_truth, by_truth);
  EXPECT_EQ(same.queries_differing, 0);
  EXPECT_EQ(same.pairs_differing, 0);
  // Perfect odometry: both labellings agree.
  const std::vector<PoseRecord> perfect = CirclePoses(2);
  const std::vector<Query> q = BuildQueries(perfect, options);
  EXPECT_EQ(CompareLabels(q, RelabelQueries(q, perfect, options, "true")).pairs_differing, 0);
}

TEST(GroundTruth, LabelPosesSwapsInTheOdometryAndOtherGroundTruthFlips) {
  const std::vector<PoseRecord> poses = DriftedSecondLap();
  const std::vector<PoseRecord> odometric = LabelPoses(poses, "odometry");
  EXPECT_EQ(odometric[150].x_m, poses[150].odo_x_m);
  EXPECT_EQ(odometric[150].theta_rad, poses[150].odo_theta_rad);
  EXPECT_EQ(LabelPoses(poses, "true")[150].x_m, poses[150].x_m);
  EXPECT_EQ(OtherGroundTruth("odometry"), "true");
  EXPECT_EQ(OtherGroundTruth("true"), "odometry");
}

TEST(GroundTruth, UnknownChoiceIsNamedByCheck) {
  ProtocolOptions options;
  options.ground_truth = "gps";
  EXPECT_EQ(options.Check(), "ground_truth: must be one of: odometry, true, overlap (got 'gps')");
}

}  // namespace
}  // namespace hoilcd
