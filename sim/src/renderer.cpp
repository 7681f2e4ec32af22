#include "hoilcd/sim/renderer.h"

#include <algorithm>
#include <cmath>

#include "hoilcd/core/parallel.h"

namespace hoilcd {

RenderOptions::RenderOptions() { Table().FillDefaults(this); }

const OptionTable<RenderOptions>& RenderOptions::Table() {
  using O = RenderOptions;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("edge_supersampling", &O::edge_supersampling, true, "supersample pixels on object, material and depth edges")
          .Add("edge_samples_per_axis", &O::edge_samples_per_axis, 2, "", OptionRange::Closed(1, 8),
               "n x n stratified samples in an edge pixel")
          .Add("specular_reflections", &O::specular_reflections, true, "one traced reflection on specular surfaces")
          .Add("threads", &O::threads, 0, "", OptionRange().AtLeast(0), "worker threads (0: every core)")
          .CodeOnly();
  return table;
}

std::string RenderOptions::Check() const { return Table().FirstProblem(*this); }

FrameRenderer::FrameRenderer(const World& world, const CameraIntrinsics& intrinsics,
                             RenderOptions options)
    : world_(world), intrinsics_(intrinsics), options_(options) {
  const std::string problem = options_.Check();
  HOILCD_CHECK_MSG(problem.empty(), problem);
  const std::string intrinsics_problem = intrinsics_.Check();
  HOILCD_CHECK_MSG(intrinsics_problem.empty(), intrinsics_problem);
  // The intrinsics are fixed, so the pixel-centre rays are computed once per renderer.
  pixel_rays_.reserve(static_cast<size_t>(intrinsics_.width) * intrinsics_.height);
  for (int y = 0; y < intrinsics_.height; ++y) {
    for (int x = 0; x < intrinsics_.width; ++x) pixel_rays_.push_back(CameraRay(x, y));
  }
}

Eigen::Vector3f FrameRenderer::CameraRay(double u, double v) const {
  Eigen::Vector3f d = intrinsics_.Unproject(u, v).cast<float>();
  d.normalize();
  return d;
}

float FrameRenderer::Shade(const RayHit& hit, const Eigen::Vector3f& origin,
                           const Eigen::Vector3f& direction, bool allow_reflection) const {
  const float environment = world_.environment_radiance();
  if (!hit.hit()) return environment;
  const InstanceInfo& info = world_.instance(hit.instance);
  const InstanceMaterial& m = info.materials[info.mesh->triangle_material[hit.triangle]];
  const Eigen::Vector3f point = origin + hit.distance_m * direction;
  const float h = std::clamp(point.z() / static_cast<float>(world_.room_height_m()), 0.0f, 1.0f);
  const float blackbody = m.blackbody_bottom + h * (m.blackbody_top - m.blackbody_bottom);
  float reflected = environment;
  if (m.specular && allow_reflection && m.emissivity < 1.0f) {
    const Eigen::Vector3f r = direction - 2.0f * direction.dot(hit.normal_world) * hit.normal_world;
    const Eigen::Vector3f o = point + 1e-3f * hit.normal_world;
    const RayHit second = world_.caster().Intersect(o, r);
    reflected = Shade(second, o, r, /*allow_reflection=*/false);
  }
  return m.emissivity * blackbody + (1.0f - m.emissivity) * reflected;
}

float FrameRenderer::Radiance(const Eigen::Vector3f& origin, const Eigen::Vector3f& direction,
                              RayHit* hit) const {
  *hit = world_.caster().Intersect(origin, direction);
  return Shade(*hit, origin, direction, options_.specular_reflections);
}

FrameBuffers FrameRenderer::Render(const CameraPose& pose) const {
  const int W = intrinsics_.width, H = intrinsics_.height;
  const Rigid3 world_from_cam = pose.WorldFromCam();
  const Eigen::Matrix3f R = world_from_cam.rotation.toRotationMatrix().cast<float>();
  const Eigen::Vector3f origin = world_from_cam.translation.cast<float>();
  const RayCaster& caster = world_.caster();
  FrameBuffers out;
  out.radiance.create(H, W, CV_32F);
  out.depth_m.create(H, W, CV_32F);
  out.instance.create(H, W, CV_32S);
  out.class_id.create(H, W, CV_32S);
  cv::Mat material(H, W, CV_32S);  // instance * 4096 + material, to find edges

  // Pass 1: one ray through each pixel centre, cast as packets of 4×4 neighbouring pixels.
  constexpr int kBlock = 4;
  static_assert(kBlock * kBlock == RayCaster::kPacketSize, "one packet per pixel block");
  ParallelForChunks(H, 8, options_.threads, [&](int64_t y0, int64_t y1, int) {
    Eigen::Vector3f directions[RayCaster::kPacketSize];
    RayHit hits[RayCaster::kPacketSize];
    int pixels[RayCaster::kPacketSize];
    for (int by = static_cast<int>(y0); by < y1; by += kBlock) {
      for (int bx = 0; bx < W; bx += kBlock) {
        int count = 0;
        for (int y = by; y < std::min<int64_t>(by + kBlock, y1); ++y) {
          for (int x = bx; x < std::min(bx + kBlock, W); ++x) {
            pixels[count] = y * W + x;
            directions[count++] = R * pixel_rays_[y * W + x];
          }
        }
        caster.IntersectPacket(origin, directions, count, hits);
        for (int i = 0; i < count; ++i) {
          const RayHit& hit = hits[i];
          const int p = pixels[i];
          out.radiance.ptr<float>()[p] =
              Shade(hit, origin, directions[i], options_.specular_reflections);
          out.depth_m.ptr<float>()[p] = hit.hit() ? hit.distance_m * pixel_rays_[p].z() : 0.0f;
          int cls = 0, mat = -1, label = -1;
          if (hit.hit()) {
            const InstanceInfo& info = world_.instance(hit.instance);
            mat = static_cast<int>(info.mesh->triangle_material[hit.triangle]);
            cls = info.materials[mat].class_id;
            label = info.label;  // a person's body parts all show the person's id
          }
          out.instance.ptr<int>()[p] = label;
          out.class_id.ptr<int>()[p] = cls;
          material.ptr<int>()[p] = label * 4096 + mat;
        }
      }
    }
  });
  if (!options_.edge_supersampling || options_.edge_samples_per_axis <= 1) return out;

  // Pass 2: pixels whose 4-neighbours see another surface (instance or material) get n×n
  // samples; smooth depth changes within one surface need none.
  cv::Mat edge(H, W, CV_8U);
  for (int y = 0; y < H; ++y) {
    const int* row = material.ptr<int>(y);
    const int* above = material.ptr<int>(std::max(y - 1, 0));
    const int* below = material.ptr<int>(std::min(y + 1, H - 1));
    uint8_t* flag = edge.ptr<uint8_t>(y);
    for (int x = 0; x < W; ++x) {
      const int m = row[x];
      flag[x] = above[x] != m || below[x] != m || (x > 0 && row[x - 1] != m) ||
                (x + 1 < W && row[x + 1] != m);
    }
  }
  out.edge_pixels = cv::countNonZero(edge);
  const int n = options_.edge_samples_per_axis;
  ParallelForChunks(H, 8, options_.threads, [&](int64_t y0, int64_t y1, int) {
    // The chunk's edge pixels block by block (4×4, so that a packet's rays stay close), their
    // samples cast in packets; each pixel's samples are summed in the order of one ray at a time.
    std::vector<int> edge_pixels;
    for (int by = static_cast<int>(y0); by < y1; by += kBlock) {
      for (int bx = 0; bx < W; bx += kBlock) {
        for (int y = by; y < std::min<int64_t>(by + kBlock, y1); ++y) {
          for (int x = bx; x < std::min(bx + kBlock, W); ++x) {
            if (edge.at<uint8_t>(y, x)) edge_pixels.push_back(y * W + x);
          }
        }
      }
    }
    std::vector<double> sums(edge_pixels.size(), 0.0);
    Eigen::Vector3f directions[RayCaster::kPacketSize];
    RayHit hits[RayCaster::kPacketSize];
    int slots[RayCaster::kPacketSize];
    int count = 0;
    auto flush = [&] {
      caster.IntersectPacket(origin, directions, count, hits);
      for (int i = 0; i < count; ++i) {
        sums[slots[i]] += Shade(hits[i], origin, directions[i], options_.specular_reflections);
      }
      count = 0;
    };
    for (size_t slot = 0; slot < edge_pixels.size(); ++slot) {
      const int x = edge_pixels[slot] % W, y = edge_pixels[slot] / W;
      for (int sy = 0; sy < n; ++sy) {
        for (int sx = 0; sx < n; ++sx) {
          slots[count] = static_cast<int>(slot);
          directions[count++] = R * CameraRay(x - 0.5 + (sx + 0.5) / n, y - 0.5 + (sy + 0.5) / n);
          if (count == RayCaster::kPacketSize) flush();
        }
      }
    }
    if (count > 0) flush();
    for (size_t slot = 0; slot < edge_pixels.size(); ++slot) {
      out.radiance.ptr<float>()[edge_pixels[slot]] = static_cast<float>(sums[slot] / (n * n));
    }
  });
  return out;
}

}  // namespace hoilcd
