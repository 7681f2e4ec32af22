#include "hoilcd/bench/slam/trajectory_metrics.h"

#include <cmath>

#include <gtest/gtest.h>

namespace hoilcd {
namespace {

std::vector<Pose2d> Curve(int n) {
  std::vector<Pose2d> poses;
  for (int i = 0; i < n; ++i) poses.push_back({0.25 * i, 0.3 * std::sin(0.2 * i), 0.1 * i});
  return poses;
}

TEST(TrajectoryMetricsTest, AteIsZeroForARigidlyMovedCopyAndUmeyamaFindsTheMotion) {
  const std::vector<Pose2d> truth = Curve(50);
  const Alignment2d motion{0.7, 3.0, -1.5};
  std::vector<Pose2d> moved;
  for (const Pose2d& p : truth) moved.push_back(motion.Apply(p));
  EXPECT_LT(AteRmseM(moved, truth), 1e-9);
  const Alignment2d back = UmeyamaAlign(truth, moved);
  EXPECT_NEAR(back.angle_rad, 0.7, 1e-9);
  EXPECT_NEAR(back.tx_m, 3.0, 1e-9);
  EXPECT_NEAR(back.ty_m, -1.5, 1e-9);
  EXPECT_LT(RpeRmseM(moved, truth, 1.0), 1e-9);
}

TEST(TrajectoryMetricsTest, AteOfAlternatingLateralOffsetsIsTheOffset) {
  std::vector<Pose2d> truth, estimate;
  for (int i = 0; i < 100; ++i) {  // both offsets at every x: no rotation can do better
    for (double offset : {-0.05, 0.05}) {
      truth.push_back({0.1 * i, 0, 0});
      estimate.push_back({0.1 * i, offset, 0});
    }
  }
  EXPECT_NEAR(AteRmseM(estimate, truth), 0.05, 1e-9);
}

TEST(TrajectoryMetricsTest, RpePairsAreOneMetreApartAlongTheReferenceAndMeasureScaleError) {
  std::vector<Pose2d> truth, estimate;
  for (int i = 0; i < 11; ++i) {
    truth.push_back({0.25 * i, 0, 0});
    estimate.push_back({0.275 * i, 0, 0});  // 10 % too long
  }
  int pairs = 0;
  EXPECT_NEAR(RpeRmseM(estimate, truth, 1.0, &pairs), 0.1, 1e-9);
  EXPECT_EQ(pairs, 2);  // 0 -> 4 and 4 -> 8
  EXPECT_EQ(RpeRmseM(estimate, truth, 10.0, &pairs), 0.0);
  EXPECT_EQ(pairs, 0);
}

// Recording runs: the robot is carried from the first run's end back to its start. The estimate's
// jump there is not the reference's, but no RPE pair spans it when the runs are segments.
TEST(TrajectoryMetricsTest, RpePairsNeverSpanTwoSegments) {
  std::vector<Pose2d> truth, estimate;
  std::vector<int> run;
  for (int r = 0; r < 2; ++r) {
    for (int i = 0; i < 11; ++i) {
      truth.push_back({0.25 * i, 0, 0});
      estimate.push_back({0.25 * i, r == 0 ? 0.0 : 0.5, 0});  // the second run offset, not distorted
      run.push_back(r);
    }
  }
  int pairs = 0;
  EXPECT_GT(RpeRmseM(estimate, truth, 1.0, &pairs), 0.1);
  EXPECT_NEAR(RpeRmseM(estimate, truth, 1.0, &pairs, run), 0, 1e-12);
  EXPECT_EQ(pairs, 4);  // 0 -> 4, 4 -> 8 in each run
}

}  // namespace
}  // namespace hoilcd
