#include "hoilcd/core/tracking/kalman_filter.h"

#include <cmath>

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

namespace hoilcd {
namespace {

TEST(KalmanFilterXYAH, BoxAndXyahRoundTrip) {
  const cv::Rect2f box(10, 20, 30, 60);
  const XyahVector xyah = BoxToXyah(box);
  EXPECT_DOUBLE_EQ(xyah(0), 25);
  EXPECT_DOUBLE_EQ(xyah(1), 50);
  EXPECT_DOUBLE_EQ(xyah(2), 0.5);
  EXPECT_DOUBLE_EQ(xyah(3), 60);
  const cv::Rect2f back = XyahToBox(xyah);
  EXPECT_FLOAT_EQ(back.x, 10);
  EXPECT_FLOAT_EQ(back.y, 20);
  EXPECT_FLOAT_EQ(back.width, 30);
  EXPECT_FLOAT_EQ(back.height, 60);
}

TEST(KalmanFilterXYAH, InitiateHasZeroVelocityAndHeightScaledCovariance) {
  const KalmanFilterXYAH kf;
  const KalmanState s = kf.Initiate({100, 80, 0.5, 40});
  EXPECT_TRUE(s.mean.tail<4>().isZero());
  EXPECT_DOUBLE_EQ(s.covariance(0, 0), (2.0 / 20 * 40) * (2.0 / 20 * 40));
  EXPECT_DOUBLE_EQ(s.covariance(4, 4), (10.0 / 160 * 40) * (10.0 / 160 * 40));
  EXPECT_TRUE((s.covariance - s.covariance.diagonal().asDiagonal().toDenseMatrix()).isZero());
}

TEST(KalmanFilterXYAH, PredictMovesByVelocityAndGrowsCovariance) {
  const KalmanFilterXYAH kf;
  KalmanState s = kf.Initiate({100, 80, 0.5, 40});
  s.mean.tail<4>() << 3, -2, 0.01, 1;
  const KalmanState p = kf.Predict(s);
  EXPECT_DOUBLE_EQ(p.mean(0), 103);
  EXPECT_DOUBLE_EQ(p.mean(1), 78);
  EXPECT_DOUBLE_EQ(p.mean(2), 0.51);
  EXPECT_DOUBLE_EQ(p.mean(3), 41);
  EXPECT_TRUE(p.mean.tail<4>().isApprox(s.mean.tail<4>()));
  for (int k = 0; k < 8; ++k) EXPECT_GT(p.covariance(k, k), s.covariance(k, k)) << k;
  // Position and velocity become correlated after one step.
  EXPECT_GT(p.covariance(0, 4), 0);
}

TEST(KalmanFilterXYAH, UpdatePullsTowardsMeasurementAndShrinksCovariance) {
  const KalmanFilterXYAH kf;
  const KalmanState p = kf.Predict(kf.Initiate({100, 80, 0.5, 40}));
  const XyahVector z(110, 70, 0.5, 44);
  const KalmanState u = kf.Update(p, z);
  for (int k : {0, 1, 3}) {
    EXPECT_LT(std::abs(u.mean(k) - z(k)), std::abs(p.mean(k) - z(k))) << k;
    // Between the prediction and the measurement, not past it.
    EXPECT_GT(std::abs(u.mean(k) - p.mean(k)), 0) << k;
    EXPECT_LT(std::abs(u.mean(k) - p.mean(k)), std::abs(z(k) - p.mean(k))) << k;
  }
  // The velocity learns the direction of the innovation.
  EXPECT_GT(u.mean(4), 0);
  EXPECT_LT(u.mean(5), 0);
  for (int k = 0; k < 8; ++k) EXPECT_LT(u.covariance(k, k), p.covariance(k, k)) << k;
  EXPECT_TRUE(u.covariance.isApprox(u.covariance.transpose(), 1e-12));
  // Still positive definite.
  EXPECT_GT(u.covariance.ldlt().vectorD().minCoeff(), 0);
}

TEST(KalmanFilterXYAH, ProjectAddsMeasurementNoise) {
  const KalmanFilterXYAH kf;
  const KalmanState s = kf.Initiate({100, 80, 0.5, 40});
  const KalmanProjection pr = kf.Project(s);
  EXPECT_TRUE(pr.mean.isApprox(s.mean.head<4>()));
  EXPECT_DOUBLE_EQ(pr.covariance(0, 0), s.covariance(0, 0) + (40.0 / 20) * (40.0 / 20));
  EXPECT_DOUBLE_EQ(pr.covariance(2, 2), s.covariance(2, 2) + 0.01);
}

TEST(KalmanFilterXYAH, RepeatedUpdatesOnAConstantVelocityTrackLearnTheVelocity) {
  const KalmanFilterXYAH kf;
  KalmanState s = kf.Initiate({50, 60, 0.5, 40});
  for (int frame = 1; frame <= 40; ++frame) {
    s = kf.Update(kf.Predict(s), XyahVector(50 + 2.0 * frame, 60 - 1.0 * frame, 0.5, 40));
  }
  EXPECT_NEAR(s.mean(4), 2.0, 0.05);
  EXPECT_NEAR(s.mean(5), -1.0, 0.05);
  EXPECT_NEAR(s.mean(0), 130, 0.5);
}

}  // namespace
}  // namespace hoilcd
