#include "hoilcd/core/tracking/kalman_filter.h"

#include <Eigen/Cholesky>

#include "hoilcd/core/util/error.h"

namespace hoilcd {

XyahVector BoxToXyah(const cv::Rect2f& box) {
  HOILCD_CHECK_MSG(box.height > 0, "box height " << box.height);
  return {box.x + box.width / 2.0, box.y + box.height / 2.0, static_cast<double>(box.width) / box.height, box.height};
}

cv::Rect2f XyahToBox(const XyahVector& xyah) {
  const double w = xyah(2) * xyah(3);
  return cv::Rect2f(static_cast<float>(xyah(0) - w / 2), static_cast<float>(xyah(1) - xyah(3) / 2),
                    static_cast<float>(w), static_cast<float>(xyah(3)));
}

KalmanFilterXYAH::KalmanFilterXYAH(double std_weight_position, double std_weight_velocity)
    : std_weight_position_(std_weight_position), std_weight_velocity_(std_weight_velocity) {
  HOILCD_CHECK(std_weight_position > 0 && std_weight_velocity > 0);
}

KalmanState KalmanFilterXYAH::Initiate(const XyahVector& measurement) const {
  const double h = measurement(3);
  Eigen::Matrix<double, 8, 1> std_dev;
  std_dev << 2 * std_weight_position_ * h, 2 * std_weight_position_ * h, 1e-2, 2 * std_weight_position_ * h,
      10 * std_weight_velocity_ * h, 10 * std_weight_velocity_ * h, 1e-5, 10 * std_weight_velocity_ * h;
  KalmanState state;
  state.mean << measurement, Eigen::Vector4d::Zero();
  state.covariance = std_dev.array().square().matrix().asDiagonal();
  return state;
}

KalmanState KalmanFilterXYAH::Predict(const KalmanState& state) const {
  const double h = state.mean(3);
  Eigen::Matrix<double, 8, 1> std_dev;
  std_dev << std_weight_position_ * h, std_weight_position_ * h, 1e-2, std_weight_position_ * h,
      std_weight_velocity_ * h, std_weight_velocity_ * h, 1e-5, std_weight_velocity_ * h;
  Eigen::Matrix<double, 8, 8> motion = Eigen::Matrix<double, 8, 8>::Identity();
  motion.topRightCorner<4, 4>() = Eigen::Matrix4d::Identity();  // dt = 1 frame
  KalmanState predicted;
  predicted.mean = motion * state.mean;
  predicted.covariance = motion * state.covariance * motion.transpose();
  predicted.covariance.diagonal() += std_dev.array().square().matrix();
  return predicted;
}

KalmanProjection KalmanFilterXYAH::Project(const KalmanState& state) const {
  const double h = state.mean(3);
  const Eigen::Vector4d std_dev(std_weight_position_ * h, std_weight_position_ * h, 1e-1, std_weight_position_ * h);
  KalmanProjection projection;
  projection.mean = state.mean.head<4>();
  projection.covariance = state.covariance.topLeftCorner<4, 4>();
  projection.covariance.diagonal() += std_dev.array().square().matrix();
  return projection;
}

KalmanState KalmanFilterXYAH::Update(const KalmanState& state, const XyahVector& measurement) const {
  const KalmanProjection projection = Project(state);
  // Gain K = P H^T S^-1 with H = [I 0]; solved through the Cholesky factor of S.
  const Eigen::Matrix<double, 8, 4> p_ht = state.covariance.leftCols<4>();
  const Eigen::LLT<Eigen::Matrix4d> llt(projection.covariance);
  HOILCD_CHECK(llt.info() == Eigen::Success);
  const Eigen::Matrix<double, 8, 4> gain = llt.solve(p_ht.transpose()).transpose();
  KalmanState updated;
  updated.mean = state.mean + gain * (measurement - projection.mean);
  updated.covariance = state.covariance - gain * projection.covariance * gain.transpose();
  return updated;
}

}  // namespace hoilcd
