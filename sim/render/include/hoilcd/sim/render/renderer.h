// Renders one frame of the World from a camera pose: per pixel the band radiance reaching the
// camera (emission + ambient or one traced specular reflection), supersampled at object edges,
// plus depth, instance id and class id. The sensor model turns radiance into temperatures.
#pragma once

#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "hoilcd/core/geometry/camera.h"
#include "hoilcd/sim/scene/render_options.h"
#include "hoilcd/sim/world/world.h"

namespace hoilcd {

struct FrameBuffers {
  cv::Mat radiance;     // CV_32F, W·m⁻²·sr⁻¹ (8–14 µm band)
  cv::Mat depth_m;      // CV_32F, distance along the camera's z axis, m
  cv::Mat instance;     // CV_32S, World instance label (a person's parts: the person's instance; -1: nothing)
  cv::Mat class_id;     // CV_32S, World class id
  int edge_pixels = 0;  // how many pixels were supersampled
};

// Render casts primary and edge-sample rays as 16-ray packets (4×4 pixel blocks) and the
// reflections of each packet as one packet, on the persistent pool of parallel.h. Its scratch
// buffers are kept between frames, so one renderer renders one frame at a time (a second
// concurrent call is an error); use a renderer per thread to render frames side by side.
class FrameRenderer {
 public:
  FrameRenderer(const World& world, const CameraIntrinsics& intrinsics, RenderOptions options);
  FrameBuffers Render(const CameraPose& pose) const;
  // The same into *out, reusing its images where they have the frame's size and type and no
  // other cv::Mat shares them (no allocation per frame).
  void Render(const CameraPose& pose, FrameBuffers* out) const;
  // Radiance along one world ray (used by Render and by tests).
  float Radiance(const Eigen::Vector3f& origin, const Eigen::Vector3f& direction, RayHit* hit) const;

 private:
  // A specular hit whose radiance waits for its reflection ray.
  struct PendingReflection {
    float* radiance;                      // where the finished radiance goes
    float emissivity, mirror, blackbody;  // mirror: MirrorShare of the hit
    float environment;                    // what the hit's material reflects diffusely
    Eigen::Vector3f origin, direction;    // the reflection ray
  };
  // At a hit `point` (world frame) at relative height h: the band radiance the material emits as a
  // blackbody (linear in height between its bottom and top values, or through its field), and the
  // radiance its surroundings send it (its environment_radiance, or `environment` when it has none,
  // plus its field's incident offset).
  struct SurfaceRadiance {
    float blackbody, surroundings;
  };
  SurfaceRadiance SurfaceAt(const InstanceInfo& info, const InstanceMaterial& m, const Eigen::Vector3f& point, float h,
                            float environment) const;
  // Per worker, kept between frames.
  struct Scratch {
    std::vector<int> edge_pixels;     // a chunk's edge pixels, 4×4 block by block
    std::vector<uint8_t> edge_flags;  // the chunk's pixels: 1 on an edge
    std::vector<float> samples;       // their samples' radiance, n×n per pixel
    std::vector<PendingReflection> pending;
  };
  // Radiance of `count` rays from `origin` of one packet into out[slots[i]]: per ray what Shade
  // returns, except that with `pending` specular hits are appended to it (their radiance written
  // by CastReflections), so that a chunk's reflections are cast as full packets.
  // With `labels`, also the hit's instance label, class id and label·4096 + material (or -1,
  // 0, -1 on a miss) at labels[slots[i]], class_ids[...], materials[...].
  void ShadePacket(const Eigen::Vector3f& origin, const Eigen::Vector3f* directions, int count,
                   const RayHitPacket& hits, float* out, const int* slots, std::vector<PendingReflection>* pending,
                   int* labels = nullptr, int* class_ids = nullptr, int* materials = nullptr) const;
  void CastReflections(std::vector<PendingReflection>* pending) const;
  // The camera of one frame: world_from_cam's rotation and the rays' origin.
  struct RayFrame {
    Eigen::Matrix3f rotation;
    Eigen::Vector3f origin;
  };
  // Pass 1 of Render over rows [y0, y1): one ray through each pixel centre, in packets of 4×4.
  void CastPixelRows(const RayFrame& frame, int64_t y0, int64_t y1, int worker, FrameBuffers* out) const;
  // Pass 2 over rows [y0, y1): n×n samples for each edge pixel; returns how many there were.
  int SupersampleEdgeRows(const RayFrame& frame, int64_t y0, int64_t y1, int worker, float* radiance) const;
  // The edge pixels of rows [y0, y1) into scratch->edge_pixels, 4×4 block by block.
  void FindEdgePixels(int64_t y0, int64_t y1, Scratch* scratch) const;
  float Shade(const RayHit& hit, const Eigen::Vector3f& origin, const Eigen::Vector3f& direction,
              bool allow_reflection) const;

  // Unit camera-frame direction of the ray through an image point (u, v), px.
  Eigen::Vector3f CameraRay(double u, double v) const;

  const World& world_;
  CameraIntrinsics intrinsics_;
  RenderOptions options_;
  std::vector<Eigen::Vector3f> pixel_rays_;  // CameraRay of every pixel centre, row-major
  // Scratch kept between frames: instance·4096 + material per pixel (edge finding), per worker.
  mutable cv::Mat material_;
  mutable std::vector<Scratch> scratch_;
  mutable std::atomic<bool> rendering_{false};
};

}  // namespace hoilcd
