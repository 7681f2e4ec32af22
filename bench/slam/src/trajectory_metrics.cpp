#include "hoilcd/bench/slam/trajectory_metrics.h"

#include <cmath>

#include <Eigen/Geometry>

#include "hoilcd/core/util/error.h"

namespace hoilcd {

Pose2d Alignment2d::Apply(const Pose2d& p) const {
  const double c = std::cos(angle_rad), s = std::sin(angle_rad);
  return {c * p.x_m - s * p.y_m + tx_m, s * p.x_m + c * p.y_m + ty_m,
          std::remainder(p.theta_rad + angle_rad, 2 * M_PI)};
}

Alignment2d UmeyamaAlign(const std::vector<Pose2d>& estimate, const std::vector<Pose2d>& reference) {
  HOILCD_CHECK(estimate.size() == reference.size());
  HOILCD_CHECK(estimate.size() >= 2);
  const Eigen::Index n = static_cast<Eigen::Index>(estimate.size());
  Eigen::Matrix2Xd src(2, n), dst(2, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    src.col(i) << estimate[i].x_m, estimate[i].y_m;
    dst.col(i) << reference[i].x_m, reference[i].y_m;
  }
  const Eigen::Matrix3d t = Eigen::umeyama(src, dst, false);
  return {std::atan2(t(1, 0), t(0, 0)), t(0, 2), t(1, 2)};
}

double AteRmseM(const std::vector<Pose2d>& estimate, const std::vector<Pose2d>& reference) {
  const Alignment2d a = UmeyamaAlign(estimate, reference);
  double sum = 0;
  for (size_t i = 0; i < estimate.size(); ++i) {
    const Pose2d p = a.Apply(estimate[i]);
    sum += std::pow(p.x_m - reference[i].x_m, 2) + std::pow(p.y_m - reference[i].y_m, 2);
  }
  return std::sqrt(sum / estimate.size());
}

double RpeRmseM(const std::vector<Pose2d>& estimate, const std::vector<Pose2d>& reference, double delta_m, int* pairs,
                const std::vector<int>& segment) {
  HOILCD_CHECK(estimate.size() == reference.size());
  HOILCD_CHECK(segment.empty() || segment.size() == reference.size());
  HOILCD_CHECK(delta_m > 0);
  double sum = 0;
  int count = 0;
  size_t i = 0;
  double travelled = 0;
  for (size_t j = 1; j < reference.size(); ++j) {
    if (!segment.empty() && segment[j] != segment[j - 1]) {
      i = j;
      travelled = 0;
      continue;
    }
    travelled += std::hypot(reference[j].x_m - reference[j - 1].x_m, reference[j].y_m - reference[j - 1].y_m);
    if (travelled < delta_m) continue;
    const Pose2d error = Between(Between(reference[i], reference[j]), Between(estimate[i], estimate[j]));
    sum += error.x_m * error.x_m + error.y_m * error.y_m;
    ++count;
    i = j;
    travelled = 0;
  }
  if (pairs) *pairs = count;
  return count ? std::sqrt(sum / count) : 0.0;
}

}  // namespace hoilcd
