// Temperature fields over a surface: what makes a garment, a table top or a wall vary inside one
// material (folds, a forearm's print, a cold corner). A material may point to one; the renderer
// adds its offset to the material's temperature at each hit and renders ε·B(T + offset) +
// (1 − ε)·(L_env + incident offset), where a room surface's field also says how what it faces
// differs from the material's mean surroundings (the patch by a cold window receives less).
#pragma once

#include <cstdint>

#include <Eigen/Core>

namespace hoilcd {

// Implementations are owned by whoever made them (the crowd, the world) and must outlive the
// frames that render them. OffsetK is called from many threads at once while a frame renders, so
// it reads state only; an owner changes that state between frames (in World::SetTime).
// What a field gives at one point.
struct FieldSample {
  float offset_k = 0;         // added to the material's temperature, K
  float incident_offset = 0;  // added to its environment_radiance, W·m⁻²·sr⁻¹
};

class SurfaceField {
 public:
  virtual ~SurfaceField() = default;
  // Offset, K, at a surface point given in the instance's own frame (it moves with the
  // instance: a garment's folds follow the body) and in the world frame.
  virtual float OffsetK(const Eigen::Vector3f& object_point, const Eigen::Vector3f& world_point) const = 0;
  // Both offsets at once (the renderer's call); fields whose surroundings are uniform keep the
  // incident offset at 0.
  virtual FieldSample Sample(const Eigen::Vector3f& object_point, const Eigen::Vector3f& world_point) const {
    return {OffsetK(object_point, world_point), 0.0f};
  }
};

// Smooth value noise in [−1, 1] with unit feature size (scale the point for other sizes),
// continuous with continuous first derivative (quintic fade), keyed by `key` through the one
// keying scheme (random.h), so each person or surface has its own stable pattern.
// Written here because it is a dozen lines: a noise library would add a dependency for one call.
float ValueNoise3(uint64_t key, const Eigen::Vector3f& point);

}  // namespace hoilcd
