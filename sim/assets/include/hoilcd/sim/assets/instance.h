// The instances the World puts in the ray caster, as the renderer and the crowd see them: each
// instance's role, name, class and per-material thermal state, and how an asset is placed.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "hoilcd/sim/assets/asset.h"
#include "hoilcd/sim/assets/surface_field.h"

namespace hoilcd {

// A material as one instance shows it this frame. Radiance is linear in height between the
// bottom and top values (walls are warmer near the ceiling); other materials have bottom == top.
// With a field, the temperature is linear in height instead, plus the field's offset at the hit.
struct InstanceMaterial {
  float temperature_c = 22;
  float temperature_top_c = 22;
  float emissivity = 0.9f;
  bool specular = false;
  float roughness_um = 0;               // specular: rms roughness, µm (MirrorShare; rest of the reflection: ambient)
  int class_id = 0;                     // class of pixels showing this material (the room has several)
  float blackbody_bottom = 0;           // band radiance at z = 0, W·m⁻²·sr⁻¹
  float blackbody_top = 0;              // band radiance at z = room height
  const SurfaceField* field = nullptr;  // not owned; null: uniform (fast path)
  // Band radiance this material reflects diffusely, W·m⁻²·sr⁻¹ (what its surroundings send it,
  // from the room's thermal solution); negative: the world's uniform environment.
  float environment_radiance = -1;
};

enum class InstanceRole { kRoom, kTable, kChair, kPerson, kObject };

struct InstanceInfo {
  InstanceRole role = InstanceRole::kObject;
  std::string name;                         // "table 3", "person 7", "cup 2"
  int class_id = 0;                         // the instance's class (its materials may refine it)
  int person_id = -1;                       // stable id for people, else -1
  int label = -1;                           // id written to the frame's instance channel: the
                                            // instance itself, or a person's pelvis for every body part
  bool fixture = false;                     // stands still all run (table, chair, scene object)
  const Asset* asset = nullptr;             // null for the room
  std::vector<InstanceMaterial> materials;  // per prototype material
  const TriangleMesh* mesh = nullptr;       // the prototype's mesh (triangle -> material index)
  Eigen::Matrix4f object_from_world = Eigen::Matrix4f::Identity();  // for fields, kept by the World
};

// World transform of an asset placed at position with a yaw about z (and uniform scale).
Eigen::Matrix4f PlacementTransform(const Eigen::Vector3d& position_m, double yaw_rad, double scale = 1.0);

}  // namespace hoilcd
