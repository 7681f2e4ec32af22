#include "hoilcd/sim/renderer.h"

#include <algorithm>
#include <cmath>

#include "hoilcd/core/parallel.h"

namespace hoilcd {

std::string RenderOptions::Check() const {
  if (edge_samples_per_axis < 1 || edge_samples_per_axis > 8) {
    return "edge_samples_per_axis must be in 1..8";
  }
  if (threads < 0) return "threads must be 0 (every core) or positive";
  return "";
}

FrameRenderer::FrameRenderer(const World& world, const CameraIntrinsics& intrinsics,
                             RenderOptions options)
    : world_(world), intrinsics_(intrinsics), options_(options) {
  HOILCD_CHECK_MSG(options_.Check().empty(), options_.Check());
  HOILCD_CHECK_MSG(intrinsics_.Check().empty(), intrinsics_.Check());
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
  FrameBuffers out;
  out.radiance.create(H, W, CV_32F);
  out.depth_m.create(H, W, CV_32F);
  out.instance.create(H, W, CV_32S);
  out.class_id.create(H, W, CV_32S);
  cv::Mat material(H, W, CV_32S);  // instance * 4096 + material, to find edges

  auto ray_dir = [&](double u, double v, float* z_per_distance) {
    Eigen::Vector3f d = intrinsics_.Unproject(u, v).cast<float>();
    d.normalize();
    *z_per_distance = d.z();
    return Eigen::Vector3f(R * d);
  };

  // Pass 1: one ray through each pixel centre.
  ParallelForChunks(H, 8, options_.threads, [&](int64_t y0, int64_t y1, int) {
    for (int y = static_cast<int>(y0); y < y1; ++y) {
      for (int x = 0; x < W; ++x) {
        float z_per_distance = 1;
        const Eigen::Vector3f d = ray_dir(x, y, &z_per_distance);
        RayHit hit;
        out.radiance.at<float>(y, x) = Radiance(origin, d, &hit);
        out.depth_m.at<float>(y, x) = hit.hit() ? hit.distance_m * z_per_distance : 0.0f;
        out.instance.at<int>(y, x) = hit.instance;
        int cls = 0, mat = -1;
        if (hit.hit()) {
          const InstanceInfo& info = world_.instance(hit.instance);
          mat = static_cast<int>(info.mesh->triangle_material[hit.triangle]);
          cls = info.materials[mat].class_id;
        }
        out.class_id.at<int>(y, x) = cls;
        material.at<int>(y, x) = hit.instance * 4096 + mat;
      }
    }
  });
  if (!options_.edge_supersampling || options_.edge_samples_per_axis <= 1) return out;

  // Pass 2: pixels whose 4-neighbours see another surface (instance or material) get n×n
  // samples; smooth depth changes within one surface need none.
  cv::Mat edge(H, W, CV_8U, cv::Scalar(0));
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      const int m = material.at<int>(y, x);
      const bool differs = (y > 0 && material.at<int>(y - 1, x) != m) ||
                           (y + 1 < H && material.at<int>(y + 1, x) != m) ||
                           (x > 0 && material.at<int>(y, x - 1) != m) ||
                           (x + 1 < W && material.at<int>(y, x + 1) != m);
      edge.at<uint8_t>(y, x) = differs ? 1 : 0;
    }
  }
  out.edge_pixels = cv::countNonZero(edge);
  const int n = options_.edge_samples_per_axis;
  ParallelForChunks(H, 8, options_.threads, [&](int64_t y0, int64_t y1, int) {
    for (int y = static_cast<int>(y0); y < y1; ++y) {
      for (int x = 0; x < W; ++x) {
        if (!edge.at<uint8_t>(y, x)) continue;
        double sum = 0;
        for (int sy = 0; sy < n; ++sy) {
          for (int sx = 0; sx < n; ++sx) {
            float unused;
            const Eigen::Vector3f d = ray_dir(x - 0.5 + (sx + 0.5) / n, y - 0.5 + (sy + 0.5) / n, &unused);
            RayHit hit;
            sum += Radiance(origin, d, &hit);
          }
        }
        out.radiance.at<float>(y, x) = static_cast<float>(sum / (n * n));
      }
    }
  });
  return out;
}

}  // namespace hoilcd
