// The bare-Embree baseline both render_bench and stages_bench compare the renderer with: the
// renderer's primary rays as 4x4-pixel rtcIntersect16 packets (coherent), hits stored, no shading.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include <Eigen/Core>
#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>

#include "hoilcd/core/geometry/camera.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/sim/world/world.h"

namespace hoilcd {

struct BareHits {
  explicit BareHits(int pixels) : distance(pixels), instance(pixels), triangle(pixels) {}
  std::vector<float> distance;
  std::vector<unsigned> instance, triangle;
};

// `cam_directions`: unit ray directions in the camera frame, one per pixel, row by row. Packets
// past the image's right or bottom edge repeat its last column or row.
inline void CastBarePackets(const World& world, const CameraIntrinsics& intrinsics,
                            const std::vector<Eigen::Vector3f>& cam_directions, const CameraPose& pose, int threads,
                            BareHits* hits) {
  const int W = intrinsics.width, H = intrinsics.height;
  RTCScene scene = world.caster().embree_scene();
  const Rigid3 world_from_cam = pose.WorldFromCam();
  const Eigen::Matrix3f R = world_from_cam.rotation.toRotationMatrix().cast<float>();
  const Eigen::Vector3f o = world_from_cam.translation.cast<float>();
  ParallelForChunks(H, 8, threads, [&](int64_t y0, int64_t y1, int) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    alignas(64) int valid[16];
    alignas(64) RTCRayHit16 rh;
    for (int64_t by = y0; by < y1; by += 4) {
      for (int bx = 0; bx < W; bx += 4) {
        for (int k = 0; k < 16; ++k) {
          const int64_t y = std::min<int64_t>(by + k / 4, H - 1);
          const int x = std::min(bx + k % 4, W - 1);
          const Eigen::Vector3f d = R * cam_directions[y * W + x];
          valid[k] = -1;
          rh.ray.org_x[k] = o.x(), rh.ray.org_y[k] = o.y(), rh.ray.org_z[k] = o.z();
          rh.ray.dir_x[k] = d.x(), rh.ray.dir_y[k] = d.y(), rh.ray.dir_z[k] = d.z();
          rh.ray.tnear[k] = 0.0f;
          rh.ray.tfar[k] = std::numeric_limits<float>::infinity();
          rh.ray.mask[k] = 0xFFFFFFFFu;
          rh.ray.flags[k] = 0;
          rh.ray.time[k] = 0;
          rh.ray.id[k] = 0;
          rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
          rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect16(valid, scene, &context, &rh);
        for (int k = 0; k < 16; ++k) {
          const int64_t i = std::min<int64_t>(by + k / 4, H - 1) * W + std::min(bx + k % 4, W - 1);
          hits->distance[i] = rh.ray.tfar[k];
          hits->instance[i] = rh.hit.instID[0][k];
          hits->triangle[i] = rh.hit.primID[k];
        }
      }
    }
  });
  benchmark::DoNotOptimize(hits->distance.data());
}

}  // namespace hoilcd
