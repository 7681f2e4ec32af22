#include "hoilcd/core/geometry/camera.h"

#include <cmath>
#include <string>

#include "hoilcd/core/util/sizes.h"

namespace hoilcd {

Eigen::Matrix4d Rigid3::Matrix() const {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = rotation.toRotationMatrix();
  m.topRightCorner<3, 1>() = translation;
  return m;
}

Eigen::Matrix3d BodyFromCamRotation() {
  Eigen::Matrix3d m;
  // Columns: camera x (right) = body -y, camera y (down) = body -z, camera z (forward) = body x.
  m << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  return m;
}

Rigid3 CameraPose::WorldFromCam() const {
  const Eigen::Matrix3d world_from_body =
      (Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch_rad, Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(roll_rad, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  Rigid3 out;
  out.rotation = Eigen::Quaterniond(world_from_body * BodyFromCamRotation()).normalized();
  out.translation = Eigen::Vector3d(x_m, y_m, z_m);
  return out;
}

CameraIntrinsics CameraIntrinsics::FromHorizontalFov(int width, int height, double hfov_deg) {
  CameraIntrinsics k;
  k.width = width;
  k.height = height;
  k.fx = k.fy = 0.5 * width / std::tan(0.5 * hfov_deg * M_PI / 180.0);
  k.cx = 0.5 * width - 0.5;
  k.cy = 0.5 * height - 0.5;
  return k;
}

double CameraIntrinsics::HorizontalFovDeg() const { return 2.0 * std::atan(0.5 * width / fx) * 180.0 / M_PI; }

double CameraIntrinsics::VerticalFovDeg() const { return 2.0 * std::atan(0.5 * height / fy) * 180.0 / M_PI; }

Eigen::Vector2d CameraIntrinsics::Project(const Eigen::Vector3d& p) const {
  return {fx * p.x() / p.z() + cx, fy * p.y() / p.z() + cy};
}

Eigen::Vector3d CameraIntrinsics::Unproject(double u, double v) const { return {(u - cx) / fx, (v - cy) / fy, 1.0}; }

std::string CameraIntrinsics::Check() const {
  if (width <= 0 || height <= 0) return "image size must be positive";
  if (width > kMaxImageSidePx || height > kMaxImageSidePx) {
    return "image size must be at most " + std::to_string(kMaxImageSidePx) + " px";
  }
  if (!(fx > 0) || !(fy > 0)) return "focal lengths must be positive";
  return "";
}

}  // namespace hoilcd
