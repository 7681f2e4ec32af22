// The constant-velocity Kalman filter ByteTrack (and DeepSORT before it) runs on a box as
// (centre x, centre y, aspect = w/h, height): 8-D state with the four velocities, noise
// proportional to the box height.
#pragma once

#include <Eigen/Core>
#include <opencv2/core/types.hpp>

namespace hoilcd {

using XyahVector = Eigen::Vector4d;  // (cx px, cy px, aspect w/h, h px)

struct KalmanState {
  Eigen::Matrix<double, 8, 1> mean;  // (cx, cy, a, h, vcx, vcy, va, vh), velocities per frame
  Eigen::Matrix<double, 8, 8> covariance;
};

struct KalmanProjection {
  XyahVector mean;
  Eigen::Matrix4d covariance;  // includes the measurement noise
};

XyahVector BoxToXyah(const cv::Rect2f& box);
cv::Rect2f XyahToBox(const XyahVector& xyah);

// Hand-written rather than cv::KalmanFilter: ByteTrack's process and measurement noise are
// rebuilt every step from the current height, which cv::KalmanFilter's fixed matrices do not do.
class KalmanFilterXYAH {
 public:
  // Standard deviations per unit of box height: position 1/20, velocity 1/160 (ByteTrack).
  explicit KalmanFilterXYAH(double std_weight_position = 1.0 / 20, double std_weight_velocity = 1.0 / 160);

  // A new track from one measurement: zero velocity, wide velocity uncertainty.
  KalmanState Initiate(const XyahVector& measurement) const;
  // One frame ahead: mean += velocity, covariance grows by the height-scaled process noise.
  KalmanState Predict(const KalmanState& state) const;
  // The state's distribution in measurement space (x, y, a, h).
  KalmanProjection Project(const KalmanState& state) const;
  // Kalman correction with a measured box.
  KalmanState Update(const KalmanState& state, const XyahVector& measurement) const;

 private:
  double std_weight_position_;
  double std_weight_velocity_;
};

}  // namespace hoilcd
