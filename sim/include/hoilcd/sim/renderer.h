// Renders one frame of the World from a camera pose: per pixel the band radiance reaching the
// camera (emission + ambient or one traced specular reflection), supersampled at object edges,
// plus depth, instance id and class id. The sensor model turns radiance into temperatures.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "hoilcd/core/camera.h"
#include "hoilcd/sim/render_options.h"
#include "hoilcd/sim/world.h"

namespace hoilcd {

struct FrameBuffers {
  cv::Mat radiance;  // CV_32F, W·m⁻²·sr⁻¹ (8–14 µm band)
  cv::Mat depth_m;   // CV_32F, distance along the camera's z axis, m
  cv::Mat instance;  // CV_32S, World instance label (a person's parts: the person's instance; -1: nothing)
  cv::Mat class_id;  // CV_32S, World class id
  int edge_pixels = 0;  // how many pixels were supersampled
};

class FrameRenderer {
 public:
  FrameRenderer(const World& world, const CameraIntrinsics& intrinsics, RenderOptions options);
  FrameBuffers Render(const CameraPose& pose) const;
  // Radiance along one world ray (used by Render and by tests).
  float Radiance(const Eigen::Vector3f& origin, const Eigen::Vector3f& direction, RayHit* hit) const;

 private:
  float Shade(const RayHit& hit, const Eigen::Vector3f& origin, const Eigen::Vector3f& direction,
              bool allow_reflection) const;

  // Unit camera-frame direction of the ray through an image point (u, v), px.
  Eigen::Vector3f CameraRay(double u, double v) const;

  const World& world_;
  CameraIntrinsics intrinsics_;
  RenderOptions options_;
  std::vector<Eigen::Vector3f> pixel_rays_;  // CameraRay of every pixel centre, row-major
};

}  // namespace hoilcd
