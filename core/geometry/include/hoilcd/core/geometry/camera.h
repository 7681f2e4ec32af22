// Pinhole camera model and rigid poses. World: x along the room, y across, z up (REP 103).
// Camera frame: x right, y down, z forward (OpenCV). Transforms are named target_from_source.
#pragma once

#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace hoilcd {

// Rigid transform p_target = rotation * p_source + translation.
struct Rigid3 {
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  Eigen::Vector3d operator*(const Eigen::Vector3d& p) const { return rotation * p + translation; }
  Rigid3 operator*(const Rigid3& other) const {
    return {rotation * other.rotation, rotation * other.translation + translation};
  }
  Rigid3 Inverse() const {
    const Eigen::Quaterniond inv = rotation.conjugate();
    return {inv, -(inv * translation)};
  }
  Eigen::Matrix4d Matrix() const;
};

// A camera pose by position and Euler angles in the world frame (REP 103): yaw about z
// (counter-clockwise positive), pitch about the body's y (left) axis, positive = looking down,
// roll about the body's x (forward) axis. At zero angles the camera looks along world +x.
struct CameraPose {
  double x_m = 0, y_m = 0, z_m = 0;
  double yaw_rad = 0, pitch_rad = 0, roll_rad = 0;

  Rigid3 WorldFromCam() const;
};

// Rotation taking camera-frame vectors (x right, y down, z forward) to body-frame vectors
// (x forward, y left, z up).
Eigen::Matrix3d BodyFromCamRotation();

struct CameraIntrinsics {
  int width = 256;    // px
  int height = 192;   // px
  double fx = 274.5;  // px, focal length along x
  double fy = 274.5;  // px
  double cx = 127.5;  // px, principal point (pixel centres at integer + 0.5 convention: 0-based centre)
  double cy = 95.5;   // px

  // Square pixels, principal point at the image centre, horizontal field of view in degrees.
  static CameraIntrinsics FromHorizontalFov(int width, int height, double hfov_deg);
  double HorizontalFovDeg() const;
  double VerticalFovDeg() const;
  // Pixel coordinates (u right, v down; pixel (i, j) has its centre at (i, j)) of a point in
  // the camera frame with z > 0.
  Eigen::Vector2d Project(const Eigen::Vector3d& point_in_cam) const;
  // Unit-less ray direction in the camera frame through pixel coordinates (u, v), z = 1.
  Eigen::Vector3d Unproject(double u, double v) const;
  // Empty string when valid, else what is wrong. A calibration (the manifest's, or derived from
  // the scene's camera), not options: no table, checked by hand.
  std::string Check() const;
};

}  // namespace hoilcd
