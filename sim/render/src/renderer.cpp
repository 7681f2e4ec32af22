#include "hoilcd/sim/render/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "hoilcd/core/util/parallel.h"

namespace hoilcd {

FrameRenderer::FrameRenderer(const World& world, const CameraIntrinsics& intrinsics, RenderOptions options)
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
  const int workers = ResolveThreadCount(options_.threads);
  scratch_.resize(workers);
}

Eigen::Vector3f FrameRenderer::CameraRay(double u, double v) const {
  Eigen::Vector3f d = intrinsics_.Unproject(u, v).cast<float>();
  d.normalize();
  return d;
}

FrameRenderer::SurfaceRadiance FrameRenderer::SurfaceAt(const InstanceInfo& info, const InstanceMaterial& m,
                                                        const Eigen::Vector3f& point, float h,
                                                        float environment) const {
  const float surroundings = m.environment_radiance >= 0 ? m.environment_radiance : environment;
  if (m.field == nullptr) return {m.blackbody_bottom + h * (m.blackbody_top - m.blackbody_bottom), surroundings};
  const Eigen::Vector3f object_point =
      info.object_from_world.topLeftCorner<3, 3>() * point + info.object_from_world.topRightCorner<3, 1>();
  const FieldSample field = m.field->Sample(object_point, point);
  const float t = m.temperature_c + h * (m.temperature_top_c - m.temperature_c) + field.offset_k;
  return {world_.radiance_table().RadianceFromCelsius(t), surroundings + field.incident_offset};
}

float FrameRenderer::Shade(const RayHit& hit, const Eigen::Vector3f& origin, const Eigen::Vector3f& direction,
                           bool allow_reflection) const {
  const float environment = world_.environment_radiance();
  if (!hit.hit()) return environment;
  const InstanceInfo& info = world_.instance(hit.instance);
  const InstanceMaterial& m = info.materials[info.mesh->triangle_material[hit.triangle]];
  const Eigen::Vector3f point = origin + hit.distance_m * direction;
  const float h = std::clamp(point.z() / static_cast<float>(world_.room_height_m()), 0.0f, 1.0f);
  const auto [blackbody, surroundings] = SurfaceAt(info, m, point, h, environment);
  float reflected = surroundings;
  if (m.specular && allow_reflection && m.emissivity < 1.0f) {
    const Eigen::Vector3f r = direction - 2.0f * direction.dot(hit.normal_world) * hit.normal_world;
    const Eigen::Vector3f o = point + 1e-3f * hit.normal_world;
    const RayHit second = world_.caster().Intersect(o, r);
    const float mirror = MirrorShare(m.roughness_um, std::abs(direction.dot(hit.normal_world)));
    reflected = mirror * Shade(second, o, r, /*allow_reflection=*/false) + (1.0f - mirror) * surroundings;
  }
  return m.emissivity * blackbody + (1.0f - m.emissivity) * reflected;
}

float FrameRenderer::Radiance(const Eigen::Vector3f& origin, const Eigen::Vector3f& direction, RayHit* hit) const {
  *hit = world_.caster().Intersect(origin, direction);
  return Shade(*hit, origin, direction, options_.specular_reflections);
}

void FrameRenderer::ShadePacket(const Eigen::Vector3f& origin, const Eigen::Vector3f* directions, int count,
                                const RayHitPacket& hits, float* out, const int* slots,
                                std::vector<PendingReflection>* pending, int* labels, int* class_ids,
                                int* materials) const {
  // As Shade, lane by lane; the same float operations in the same order.
  const float environment = world_.environment_radiance();
  const float room_height_m = static_cast<float>(world_.room_height_m());
  for (int i = 0; i < count; ++i) {
    float& radiance = out[slots[i]];
    if (hits.instance[i] < 0) {
      radiance = environment;
      if (labels != nullptr) {
        labels[slots[i]] = -1;
        class_ids[slots[i]] = 0;
        materials[slots[i]] = -4096 - 1;
      }
      continue;
    }
    const Eigen::Vector3f& direction = directions[i];
    const InstanceInfo& info = world_.instance(hits.instance[i]);
    const int material = static_cast<int>(info.mesh->triangle_material[hits.triangle[i]]);
    const InstanceMaterial& m = info.materials[material];
    if (labels != nullptr) {
      labels[slots[i]] = info.label;  // a person's body parts all show the person's id
      class_ids[slots[i]] = m.class_id;
      materials[slots[i]] = info.label * 4096 + material;
    }
    const Eigen::Vector3f point = origin + hits.distance_m[i] * direction;
    const float h = std::clamp(point.z() / room_height_m, 0.0f, 1.0f);
    const auto [blackbody, surroundings] = SurfaceAt(info, m, point, h, environment);
    if (pending != nullptr && m.specular && m.emissivity < 1.0f) {
      const Eigen::Vector3f n = world_.caster().Hit(hits, i, direction).normal_world;
      pending->push_back({&radiance, m.emissivity, MirrorShare(m.roughness_um, std::abs(direction.dot(n))), blackbody,
                          surroundings, point + 1e-3f * n, direction - 2.0f * direction.dot(n) * n});
      continue;
    }
    radiance = m.emissivity * blackbody + (1.0f - m.emissivity) * surroundings;
  }
}

void FrameRenderer::CastReflections(std::vector<PendingReflection>* pending) const {
  Eigen::Vector3f origins[kRayPacketSize], directions[kRayPacketSize];
  RayHitPacket hits, one;
  float reflected = 0.0f;
  const int slot = 0;
  for (size_t begin = 0; begin < pending->size(); begin += kRayPacketSize) {
    const int count = static_cast<int>(std::min<size_t>(kRayPacketSize, pending->size() - begin));
    for (int i = 0; i < count; ++i) {
      origins[i] = (*pending)[begin + i].origin;
      directions[i] = (*pending)[begin + i].direction;
    }
    world_.caster().IntersectPacket(origins, directions, count, &hits);
    for (int i = 0; i < count; ++i) {
      // Shade(second, o, r, allow_reflection = false) of each reflection ray.
      one.instance[0] = hits.instance[i];
      one.triangle[0] = hits.triangle[i];
      one.distance_m[0] = hits.distance_m[i];
      ShadePacket(origins[i], &directions[i], 1, one, &reflected, &slot, nullptr);
      const PendingReflection& p = (*pending)[begin + i];
      *p.radiance = p.emissivity * p.blackbody +
                    (1.0f - p.emissivity) * (p.mirror * reflected + (1.0f - p.mirror) * p.environment);
    }
  }
  pending->clear();
}

FrameBuffers FrameRenderer::Render(const CameraPose& pose) const {
  FrameBuffers out;
  Render(pose, &out);
  return out;
}

namespace {

// Gives *image the size and type, reusing its buffer unless another cv::Mat shares it.
void Reuse(int rows, int cols, int type, cv::Mat* image) {
  if (image->u != nullptr && image->u->refcount > 1) image->release();
  image->create(rows, cols, type);
}

}  // namespace

namespace {
constexpr int kBlock = 4;             // pixels per side of a ray packet's block
constexpr int64_t kRowsPerChunk = 8;  // rows per parallel chunk
static_assert(kBlock * kBlock == kRayPacketSize, "one packet per pixel block");
}  // namespace

void FrameRenderer::Render(const CameraPose& pose, FrameBuffers* out) const {
  HOILCD_CHECK_MSG(!rendering_.exchange(true),
                   "FrameRenderer::Render called while it renders another frame; use one renderer per thread");
  struct Done {
    std::atomic<bool>& flag;
    ~Done() { flag = false; }
  } done{rendering_};
  const int W = intrinsics_.width, H = intrinsics_.height;
  const Rigid3 world_from_cam = pose.WorldFromCam();
  const RayFrame frame{world_from_cam.rotation.toRotationMatrix().cast<float>(),
                       world_from_cam.translation.cast<float>()};
  Reuse(H, W, CV_32F, &out->radiance);
  Reuse(H, W, CV_32F, &out->depth_m);
  Reuse(H, W, CV_32S, &out->instance);
  Reuse(H, W, CV_32S, &out->class_id);
  out->edge_pixels = 0;
  material_.create(H, W, CV_32S);  // instance * 4096 + material, to find edges

  // Pass 1: one ray through each pixel centre; each chunk's reflection rays after its last packet.
  ParallelForChunks(H, kRowsPerChunk, options_.threads,
                    [&](int64_t y0, int64_t y1, int worker) { CastPixelRows(frame, y0, y1, worker, out); });
  if (!options_.edge_supersampling || options_.edge_samples_per_axis <= 1) return;

  // Pass 2: pixels whose 4-neighbours see another surface (instance or material) get n×n
  // samples; smooth depth changes within one surface need none.
  std::atomic<int> edge_count{0};
  float* radiance_px = out->radiance.ptr<float>();
  ParallelForChunks(H, kRowsPerChunk, options_.threads, [&](int64_t y0, int64_t y1, int worker) {
    edge_count += SupersampleEdgeRows(frame, y0, y1, worker, radiance_px);
  });
  out->edge_pixels = edge_count;
}

void FrameRenderer::CastPixelRows(const RayFrame& frame, int64_t y0, int64_t y1, int worker, FrameBuffers* out) const {
  const int W = intrinsics_.width;
  float* radiance_px = out->radiance.ptr<float>();
  float* depth_px = out->depth_m.ptr<float>();
  int* instance_px = out->instance.ptr<int>();
  int* class_px = out->class_id.ptr<int>();
  int* material_px = material_.ptr<int>();
  std::vector<PendingReflection>* pending = options_.specular_reflections ? &scratch_[worker].pending : nullptr;
  Eigen::Vector3f directions[kRayPacketSize];
  RayHitPacket hits;
  int pixels[kRayPacketSize];
  for (int by = static_cast<int>(y0); by < y1; by += kBlock) {
    for (int bx = 0; bx < W; bx += kBlock) {
      int count = 0;
      for (int y = by; y < std::min<int64_t>(by + kBlock, y1); ++y) {
        for (int x = bx; x < std::min(bx + kBlock, W); ++x) {
          pixels[count] = y * W + x;
          directions[count++] = frame.rotation * pixel_rays_[y * W + x];
        }
      }
      world_.caster().IntersectPacket(frame.origin, directions, count, &hits);
      ShadePacket(frame.origin, directions, count, hits, radiance_px, pixels, pending, instance_px, class_px,
                  material_px);
      for (int i = 0; i < count; ++i) {
        const int p = pixels[i];
        depth_px[p] = hits.instance[i] >= 0 ? hits.distance_m[i] * pixel_rays_[p].z() : 0.0f;
      }
    }
  }
  if (pending != nullptr) CastReflections(pending);
}

void FrameRenderer::FindEdgePixels(int64_t y0, int64_t y1, Scratch* scratch) const {
  const int W = intrinsics_.width, H = intrinsics_.height;
  const int* material_px = material_.ptr<int>();
  std::vector<int>& edge_pixels = scratch->edge_pixels;
  std::vector<uint8_t>& flags = scratch->edge_flags;
  edge_pixels.clear();
  flags.resize(static_cast<size_t>(y1 - y0) * W);
  for (int64_t y = y0; y < y1; ++y) {  // branch-free, so that it runs in vector lanes
    const int* row = material_px + y * W;
    const int* above = material_px + std::max<int64_t>(y - 1, 0) * W;
    const int* below = material_px + std::min<int64_t>(y + 1, H - 1) * W;
    uint8_t* flag = flags.data() + (y - y0) * W;
    for (int x = 0; x < W; ++x) flag[x] = (above[x] != row[x]) | (below[x] != row[x]);
    for (int x = 1; x < W; ++x) flag[x] |= row[x - 1] != row[x];
    for (int x = 0; x + 1 < W; ++x) flag[x] |= row[x + 1] != row[x];
  }
  for (int by = static_cast<int>(y0); by < y1; by += kBlock) {
    for (int bx = 0; bx < W; bx += kBlock) {
      for (int y = by; y < std::min<int64_t>(by + kBlock, y1); ++y) {
        const uint8_t* flag = flags.data() + (y - y0) * W;
        uint32_t any = 0;  // most blocks have no edge: one 4-byte test for a block's row
        if (bx + kBlock <= W)
          std::memcpy(&any, flag + bx, sizeof any);
        else
          any = 1;
        if (any == 0) continue;
        for (int x = bx; x < std::min(bx + kBlock, W); ++x) {
          if (flag[x]) edge_pixels.push_back(y * W + x);
        }
      }
    }
  }
}

// Each chunk finds its own edge pixels (pass 1 has labelled every row), casts their samples in
// packets (block by block, so that a packet's rays stay close), then their reflections, and
// sums each pixel's samples in the order of one ray at a time.
int FrameRenderer::SupersampleEdgeRows(const RayFrame& frame, int64_t y0, int64_t y1, int worker,
                                       float* radiance) const {
  const int W = intrinsics_.width;
  const int n = options_.edge_samples_per_axis;
  Scratch& scratch = scratch_[worker];
  std::vector<PendingReflection>* pending = options_.specular_reflections ? &scratch.pending : nullptr;
  FindEdgePixels(y0, y1, &scratch);
  const std::vector<int>& edge_pixels = scratch.edge_pixels;
  // Sample k of edge pixel `slot` at samples[slot·n² + k]; pending reflections point into it,
  // so it is sized once, before any packet.
  std::vector<float>& samples = scratch.samples;
  samples.resize(edge_pixels.size() * n * n);
  Eigen::Vector3f directions[kRayPacketSize];
  RayHitPacket hits;
  int slots[kRayPacketSize];
  int count = 0;
  auto flush = [&] {
    world_.caster().IntersectPacket(frame.origin, directions, count, &hits);
    ShadePacket(frame.origin, directions, count, hits, samples.data(), slots, pending);
    count = 0;
  };
  int sample = 0;
  for (const int pixel : edge_pixels) {
    const int x = pixel % W, y = pixel / W;
    for (int sy = 0; sy < n; ++sy) {
      for (int sx = 0; sx < n; ++sx) {
        slots[count] = sample++;
        directions[count++] = frame.rotation * CameraRay(x - 0.5 + (sx + 0.5) / n, y - 0.5 + (sy + 0.5) / n);
        if (count == kRayPacketSize) flush();
      }
    }
  }
  if (count > 0) flush();
  if (pending != nullptr) CastReflections(pending);
  for (size_t slot = 0; slot < edge_pixels.size(); ++slot) {
    double sum = 0.0;
    for (int k = 0; k < n * n; ++k) sum += samples[slot * n * n + k];
    radiance[edge_pixels[slot]] = static_cast<float>(sum / (n * n));
  }
  return static_cast<int>(edge_pixels.size());
}

}  // namespace hoilcd
