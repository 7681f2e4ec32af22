// Embree 3 ray casting over instanced triangle meshes. Each distinct mesh (an asset, the room)
// is a prototype scene built once; placements are Embree instances whose transforms can change
// every frame (people move by transform updates, never by rebuilding geometry).
#pragma once

#include <limits>
#include <memory>
#include <vector>

#include <Eigen/Core>

struct RTCSceneTy;  // Embree's scene type (RTCScene is RTCSceneTy*)

namespace hoilcd {

struct TriangleMesh;

struct RayHit {
  float distance_m = 0;                                    // along the (unit) ray direction; infinity on a miss
  int instance = -1;                                       // instance id from AddInstance, -1 on a miss
  int triangle = -1;                                       // triangle index within the prototype mesh
  Eigen::Vector3f normal_world = Eigen::Vector3f::Zero();  // unit geometric normal, facing the ray
  bool hit() const { return instance >= 0; }
};

constexpr int kRayPacketSize = 16;

// Closest hits of a packet of rays, structure of arrays, without RayHit's world normal (a matrix
// product and a square root per hit that a renderer needs only on specular surfaces; RayCaster::
// Hit completes one lane). Lanes at and beyond the packet's count are undefined.
struct RayHitPacket {
  float distance_m[kRayPacketSize];  // infinity on a miss
  int instance[kRayPacketSize];      // -1 on a miss
  int triangle[kRayPacketSize];
  float normal_object[3][kRayPacketSize];  // geometric normal in the prototype's frame, not unit
};

class RayCaster {
 public:
  RayCaster();
  ~RayCaster();
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  // Builds a prototype from a mesh (positions in the prototype's own frame); returns its id.
  int AddPrototype(const TriangleMesh& mesh);
  // Places a prototype; returns the instance id (consecutive from 0).
  int AddInstance(int prototype, const Eigen::Matrix4f& world_from_object);
  void SetInstanceTransform(int instance, const Eigen::Matrix4f& world_from_object);
  // Must be called after adding instances or moving them, before casting rays.
  void Commit();

  int num_instances() const;
  int prototype_of(int instance) const;
  const Eigen::Matrix4f& transform_of(int instance) const;

  // Closest hit along origin + t * direction, t in (t_min, t_max). Thread-safe after Commit().
  RayHit Intersect(const Eigen::Vector3f& origin, const Eigen::Vector3f& direction, float t_min = 0.0f,
                   float t_max = std::numeric_limits<float>::infinity()) const;
  // Closest hits of `count` (1..kPacketSize) rays from one origin with Embree's packet
  // traversal (coherent; rtcIntersect16, or rtcIntersect8 / single rays where the CPU lacks
  // native 16- / 8-wide packets): much faster than single rays when the directions are close,
  // e.g. a 4×4 block of pixels. hits[i] is what Intersect(origin, directions[i]) returns (up to
  // the packet kernel's rounding). Thread-safe after Commit().
  static constexpr int kPacketSize = kRayPacketSize;
  void IntersectPacket(const Eigen::Vector3f& origin, const Eigen::Vector3f* directions, int count, RayHit* hits) const;
  // The same into a RayHitPacket (no per-hit normal).
  void IntersectPacket(const Eigen::Vector3f& origin, const Eigen::Vector3f* directions, int count,
                       RayHitPacket* hits) const;
  // Rays with an origin each (e.g. reflections off one surface; cast without the coherent flag).
  void IntersectPacket(const Eigen::Vector3f* origins, const Eigen::Vector3f* directions, int count,
                       RayHitPacket* hits) const;
  // Lane i of a packet as Intersect returns it, normal included.
  RayHit Hit(const RayHitPacket& hits, int i, const Eigen::Vector3f& direction) const;
  // Closest hit against one instance alone (ignoring everything else): for visibility ratios.
  RayHit IntersectInstance(int instance, const Eigen::Vector3f& origin, const Eigen::Vector3f& direction) const;
  // The same for a packet of `count` (1..kPacketSize) rays from one origin (coherent).
  void IntersectInstancePacket(int instance, const Eigen::Vector3f& origin, const Eigen::Vector3f* directions,
                               int count, RayHitPacket* hits) const;

  // The top-level Embree scene (valid after Commit()), for callers that cast rays with Embree
  // directly, e.g. the bare-Embree baseline of benchmarks/render_bench.cpp.
  RTCSceneTy* embree_scene() const;

 private:
  void CastSoa(RTCSceneTy* scene, const Eigen::Vector3f* origins, int origin_stride, const Eigen::Vector3f* directions,
               int count, bool coherent, RayHitPacket* hits) const;

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hoilcd
