#include "hoilcd/sim/world/ray_caster.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

#include <Eigen/Dense>
#include <embree3/rtcore.h>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/sim/assets/asset.h"

namespace hoilcd {
namespace {

// Embree reports errors through a callback (registered once per device); exceptions must not
// cross Embree's C frames, so the message is stored and thrown after the call returns.
void EmbreeError(void* user, RTCError code, const char* message) {
  auto* last_error = static_cast<std::string*>(user);
  if (last_error->empty()) {
    *last_error = "Embree error " + std::to_string(static_cast<int>(code)) + ": " + (message ? message : "");
  }
}

// Small RAII owners of Embree handles.
struct DeviceHandle {
  RTCDevice device = rtcNewDevice(nullptr);
  ~DeviceHandle() { rtcReleaseDevice(device); }
};
struct SceneHandle {
  explicit SceneHandle(RTCDevice device) : scene(rtcNewScene(device)) {}
  ~SceneHandle() { rtcReleaseScene(scene); }
  SceneHandle(const SceneHandle&) = delete;
  SceneHandle& operator=(const SceneHandle&) = delete;
  RTCScene scene;
};
struct GeometryHandle {
  explicit GeometryHandle(RTCGeometry g) : geometry(g) {}
  ~GeometryHandle() { rtcReleaseGeometry(geometry); }
  GeometryHandle(const GeometryHandle&) = delete;
  GeometryHandle& operator=(const GeometryHandle&) = delete;
  RTCGeometry geometry;
};

RTCRayHit MakeRay(const Eigen::Vector3f& o, const Eigen::Vector3f& d, float t_min, float t_max) {
  RTCRayHit rh;
  rh.ray.org_x = o.x();
  rh.ray.org_y = o.y();
  rh.ray.org_z = o.z();
  rh.ray.dir_x = d.x();
  rh.ray.dir_y = d.y();
  rh.ray.dir_z = d.z();
  rh.ray.tnear = t_min;
  rh.ray.tfar = t_max;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.flags = 0;
  rh.ray.time = 0;
  rh.ray.id = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

// Packet casts of K rays (K = 8 or 16) from one origin; hits come back as single RTCRayHits.
void IntersectK(const int* valid, RTCScene scene, RTCIntersectContext* context, RTCRayHit8* rh) {
  rtcIntersect8(valid, scene, context, rh);
}
void IntersectK(const int* valid, RTCScene scene, RTCIntersectContext* context, RTCRayHit16* rh) {
  rtcIntersect16(valid, scene, context, rh);
}
template <int K>
using EmbreePacket = std::conditional_t<K == 8, RTCRayHit8, RTCRayHit16>;

// origins: one per ray, or (origin_stride 0) one for all.
template <int K>
void CastPacketK(RTCScene scene, RTCIntersectContext* context, const Eigen::Vector3f* origins, int origin_stride,
                 const Eigen::Vector3f* directions, int count, EmbreePacket<K>* packet) {
  alignas(64) int valid[K];
  EmbreePacket<K>& rh = *packet;
  // Field by field, so that the constant fields fill in vector stores; lanes past `count` are
  // invalid and repeat the last ray.
  for (int i = 0; i < K; ++i) {
    valid[i] = i < count ? -1 : 0;
    rh.ray.tnear[i] = 0.0f;
    rh.ray.tfar[i] = std::numeric_limits<float>::infinity();
    rh.ray.mask[i] = 0xFFFFFFFFu;
    rh.ray.flags[i] = 0;
    rh.ray.time[i] = 0;
    rh.ray.id[i] = 0;
    rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID[i] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
  }
  for (int i = 0; i < K; ++i) {
    const int lane = std::min(i, count - 1);
    const Eigen::Vector3f& d = directions[lane];
    const Eigen::Vector3f& origin = origins[lane * origin_stride];
    rh.ray.org_x[i] = origin.x();
    rh.ray.org_y[i] = origin.y();
    rh.ray.org_z[i] = origin.z();
    rh.ray.dir_x[i] = d.x();
    rh.ray.dir_y[i] = d.y();
    rh.ray.dir_z[i] = d.z();
  }
  IntersectK(valid, scene, context, &rh);
}

template <int K>
void CastPacket(RTCScene scene, RTCIntersectContext* context, const Eigen::Vector3f& origin,
                const Eigen::Vector3f* directions, int count, RTCRayHit* out) {
  alignas(64) EmbreePacket<K> rh;
  CastPacketK<K>(scene, context, &origin, 0, directions, count, &rh);
  for (int i = 0; i < count; ++i) {
    out[i].ray.tfar = rh.ray.tfar[i];
    out[i].hit.geomID = rh.hit.geomID[i];
    out[i].hit.primID = rh.hit.primID[i];
    out[i].hit.instID[0] = rh.hit.instID[0][i];
    out[i].hit.Ng_x = rh.hit.Ng_x[i];
    out[i].hit.Ng_y = rh.hit.Ng_y[i];
    out[i].hit.Ng_z = rh.hit.Ng_z[i];
  }
}

}  // namespace

struct RayCaster::Impl {
  DeviceHandle device;
  std::string last_error;  // written by EmbreeError during build calls (single-threaded)

  void ThrowIfError() {
    if (!last_error.empty()) {
      const std::string message = last_error;
      last_error.clear();
      throw std::runtime_error(message);
    }
  }
  int packet_width = 1;  // widest ray packet the CPU runs natively: 16, 8, or 1 (single rays)
  std::unique_ptr<SceneHandle> top;
  std::vector<std::unique_ptr<SceneHandle>> prototypes;
  std::vector<std::unique_ptr<GeometryHandle>> instances;
  std::vector<int> instance_prototype;
  std::vector<Eigen::Matrix4f> instance_transform;
  std::vector<Eigen::Matrix3f> instance_normal_matrix;  // inverse-transpose of the linear part
  std::vector<Eigen::Matrix4f> instance_inverse;

  RayHit Finish(const RTCRayHit& rh, const Eigen::Vector3f& direction, int forced_instance) const {
    RayHit hit;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
      hit.distance_m = std::numeric_limits<float>::infinity();
      return hit;
    }
    hit.distance_m = rh.ray.tfar;
    hit.instance = forced_instance >= 0 ? forced_instance : static_cast<int>(rh.hit.instID[0]);
    hit.triangle = static_cast<int>(rh.hit.primID);
    Eigen::Vector3f n = instance_normal_matrix[hit.instance] * Eigen::Vector3f(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
    n.normalize();
    if (n.dot(direction) > 0) n = -n;
    hit.normal_world = n;
    return hit;
  }
};

RayCaster::RayCaster() : impl_(std::make_unique<Impl>()) {
  HOILCD_CHECK_MSG(impl_->device.device != nullptr, "rtcNewDevice failed");
  rtcSetDeviceErrorFunction(impl_->device.device, EmbreeError, &impl_->last_error);
  if (rtcGetDeviceProperty(impl_->device.device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED)) {
    impl_->packet_width = 16;
  } else if (rtcGetDeviceProperty(impl_->device.device, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED)) {
    impl_->packet_width = 8;
  }
  impl_->top = std::make_unique<SceneHandle>(impl_->device.device);
  // Instances move every frame: a fast rebuild of the small top-level BVH beats a good one.
  rtcSetSceneFlags(impl_->top->scene, RTC_SCENE_FLAG_DYNAMIC);
  rtcSetSceneBuildQuality(impl_->top->scene, RTC_BUILD_QUALITY_LOW);
}

RayCaster::~RayCaster() = default;

int RayCaster::AddPrototype(const TriangleMesh& mesh) {
  HOILCD_CHECK(mesh.indices.size() % 3 == 0 && !mesh.positions_m.empty());
  auto scene = std::make_unique<SceneHandle>(impl_->device.device);
  rtcSetSceneBuildQuality(scene->scene, RTC_BUILD_QUALITY_HIGH);
  GeometryHandle geometry(rtcNewGeometry(impl_->device.device, RTC_GEOMETRY_TYPE_TRIANGLE));
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry.geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.positions_m.size()));
  for (size_t i = 0; i < mesh.positions_m.size(); ++i) {
    vertices[3 * i + 0] = mesh.positions_m[i].x();
    vertices[3 * i + 1] = mesh.positions_m[i].y();
    vertices[3 * i + 2] = mesh.positions_m[i].z();
  }
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geometry.geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.indices.size() / 3));
  for (size_t i = 0; i < mesh.indices.size(); ++i) indices[i] = mesh.indices[i];
  rtcCommitGeometry(geometry.geometry);
  rtcAttachGeometry(scene->scene, geometry.geometry);
  rtcCommitScene(scene->scene);
  impl_->ThrowIfError();
  impl_->prototypes.push_back(std::move(scene));
  return static_cast<int>(impl_->prototypes.size()) - 1;
}

int RayCaster::AddInstance(int prototype, const Eigen::Matrix4f& world_from_object) {
  HOILCD_CHECK(prototype >= 0 && prototype < static_cast<int>(impl_->prototypes.size()));
  auto geometry = std::make_unique<GeometryHandle>(rtcNewGeometry(impl_->device.device, RTC_GEOMETRY_TYPE_INSTANCE));
  rtcSetGeometryInstancedScene(geometry->geometry, impl_->prototypes[prototype]->scene);
  const unsigned id = rtcAttachGeometry(impl_->top->scene, geometry->geometry);
  HOILCD_CHECK(id == impl_->instances.size());
  impl_->instances.push_back(std::move(geometry));
  impl_->instance_prototype.push_back(prototype);
  impl_->instance_transform.emplace_back();
  impl_->instance_normal_matrix.emplace_back();
  impl_->instance_inverse.emplace_back();
  SetInstanceTransform(static_cast<int>(id), world_from_object);
  return static_cast<int>(id);
}

void RayCaster::SetInstanceTransform(int instance, const Eigen::Matrix4f& world_from_object) {
  HOILCD_CHECK(instance >= 0 && instance < num_instances());
  RTCGeometry g = impl_->instances[instance]->geometry;
  rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, world_from_object.data());
  rtcCommitGeometry(g);
  impl_->instance_transform[instance] = world_from_object;
  impl_->instance_normal_matrix[instance] = world_from_object.topLeftCorner<3, 3>().inverse().transpose();
  impl_->instance_inverse[instance] = world_from_object.inverse();
}

void RayCaster::Commit() {
  // The top level holds a few hundred instances: its build takes microseconds, while Embree's
  // TBB workers, woken for it every frame, would then spin for far longer.
  RunOnCallingThread([&] { rtcCommitScene(impl_->top->scene); });
  impl_->ThrowIfError();
}

int RayCaster::num_instances() const { return static_cast<int>(impl_->instances.size()); }
int RayCaster::prototype_of(int instance) const { return impl_->instance_prototype.at(instance); }
const Eigen::Matrix4f& RayCaster::transform_of(int instance) const { return impl_->instance_transform.at(instance); }

RTCSceneTy* RayCaster::embree_scene() const { return impl_->top->scene; }

RayHit RayCaster::Intersect(const Eigen::Vector3f& origin, const Eigen::Vector3f& direction, float t_min,
                            float t_max) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh = MakeRay(origin, direction, t_min, t_max);
  rtcIntersect1(impl_->top->scene, &context, &rh);
  return impl_->Finish(rh, direction, -1);
}

void RayCaster::IntersectPacket(const Eigen::Vector3f& origin, const Eigen::Vector3f* directions, int count,
                                RayHit* hits) const {
  HOILCD_CHECK(count >= 1 && count <= kPacketSize);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  RTCRayHit single[kPacketSize];
  if (impl_->packet_width == 16) {
    CastPacket<16>(impl_->top->scene, &context, origin, directions, count, single);
  } else if (impl_->packet_width == 8) {
    for (int begin = 0; begin < count; begin += 8) {
      CastPacket<8>(impl_->top->scene, &context, origin, directions + begin, std::min(8, count - begin),
                    single + begin);
    }
  } else {
    for (int i = 0; i < count; ++i) {
      single[i] = MakeRay(origin, directions[i], 0.0f, std::numeric_limits<float>::infinity());
      rtcIntersect1(impl_->top->scene, &context, &single[i]);
    }
  }
  for (int i = 0; i < count; ++i) hits[i] = impl_->Finish(single[i], directions[i], -1);
}

void RayCaster::IntersectPacket(const Eigen::Vector3f& origin, const Eigen::Vector3f* directions, int count,
                                RayHitPacket* hits) const {
  CastSoa(impl_->top->scene, &origin, 0, directions, count, /*coherent=*/true, hits);
}

void RayCaster::IntersectPacket(const Eigen::Vector3f* origins, const Eigen::Vector3f* directions, int count,
                                RayHitPacket* hits) const {
  CastSoa(impl_->top->scene, origins, 1, directions, count, /*coherent=*/false, hits);
}

void RayCaster::CastSoa(RTCScene scene, const Eigen::Vector3f* origins, int origin_stride,
                        const Eigen::Vector3f* directions, int count, bool coherent, RayHitPacket* hits) const {
  HOILCD_CHECK(count >= 1 && count <= kPacketSize);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  if (coherent) context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  // Embree's hits straight into the packet's arrays, misses marked as Finish marks them.
  auto take = [hits](int i, float tfar, unsigned geom, unsigned prim, unsigned inst, float nx, float ny, float nz) {
    const bool hit = geom != RTC_INVALID_GEOMETRY_ID;
    hits->distance_m[i] = hit ? tfar : std::numeric_limits<float>::infinity();
    hits->instance[i] = hit ? static_cast<int>(inst) : -1;
    hits->triangle[i] = hit ? static_cast<int>(prim) : -1;
    hits->normal_object[0][i] = nx;
    hits->normal_object[1][i] = ny;
    hits->normal_object[2][i] = nz;
  };
  if (impl_->packet_width == 16) {
    alignas(64) RTCRayHit16 rh;
    CastPacketK<16>(scene, &context, origins, origin_stride, directions, count, &rh);
    for (int i = 0; i < count; ++i) {
      take(i, rh.ray.tfar[i], rh.hit.geomID[i], rh.hit.primID[i], rh.hit.instID[0][i], rh.hit.Ng_x[i], rh.hit.Ng_y[i],
           rh.hit.Ng_z[i]);
    }
  } else if (impl_->packet_width == 8) {
    for (int begin = 0; begin < count; begin += 8) {
      alignas(64) RTCRayHit8 rh;
      const int n = std::min(8, count - begin);
      CastPacketK<8>(scene, &context, origins + begin * origin_stride, origin_stride, directions + begin, n, &rh);
      for (int i = 0; i < n; ++i) {
        take(begin + i, rh.ray.tfar[i], rh.hit.geomID[i], rh.hit.primID[i], rh.hit.instID[0][i], rh.hit.Ng_x[i],
             rh.hit.Ng_y[i], rh.hit.Ng_z[i]);
      }
    }
  } else {
    for (int i = 0; i < count; ++i) {
      RTCRayHit rh = MakeRay(origins[i * origin_stride], directions[i], 0.0f, std::numeric_limits<float>::infinity());
      rtcIntersect1(scene, &context, &rh);
      take(i, rh.ray.tfar, rh.hit.geomID, rh.hit.primID, rh.hit.instID[0], rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
    }
  }
}

RayHit RayCaster::Hit(const RayHitPacket& hits, int i, const Eigen::Vector3f& direction) const {
  RTCRayHit rh;
  rh.ray.tfar = hits.distance_m[i];
  rh.hit.geomID = hits.instance[i] >= 0 ? 0u : RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = static_cast<unsigned>(hits.triangle[i]);
  rh.hit.instID[0] = static_cast<unsigned>(hits.instance[i]);
  rh.hit.Ng_x = hits.normal_object[0][i];
  rh.hit.Ng_y = hits.normal_object[1][i];
  rh.hit.Ng_z = hits.normal_object[2][i];
  return impl_->Finish(rh, direction, -1);
}

RayHit RayCaster::IntersectInstance(int instance, const Eigen::Vector3f& origin,
                                    const Eigen::Vector3f& direction) const {
  const Eigen::Matrix4f& inv = impl_->instance_inverse.at(instance);
  const Eigen::Vector3f o = inv.topLeftCorner<3, 3>() * origin + inv.topRightCorner<3, 1>();
  const Eigen::Vector3f d = inv.topLeftCorner<3, 3>() * direction;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  // The object-space direction is not unit length; t stays the world distance along the ray.
  RTCRayHit rh = MakeRay(o, d, 0.0f, std::numeric_limits<float>::infinity());
  rtcIntersect1(impl_->prototypes[impl_->instance_prototype[instance]]->scene, &context, &rh);
  return impl_->Finish(rh, direction, instance);
}

void RayCaster::IntersectInstancePacket(int instance, const Eigen::Vector3f& origin, const Eigen::Vector3f* directions,
                                        int count, RayHitPacket* hits) const {
  HOILCD_CHECK(count >= 1 && count <= kPacketSize);
  // In the prototype's frame, as IntersectInstance (t stays the world distance along the ray).
  const Eigen::Matrix4f& inv = impl_->instance_inverse.at(instance);
  const Eigen::Vector3f o = inv.topLeftCorner<3, 3>() * origin + inv.topRightCorner<3, 1>();
  Eigen::Vector3f d[kPacketSize];
  for (int i = 0; i < count; ++i) d[i] = inv.topLeftCorner<3, 3>() * directions[i];
  CastSoa(impl_->prototypes[impl_->instance_prototype[instance]]->scene, &o, 0, d, count,
          /*coherent=*/true, hits);
  for (int i = 0; i < count; ++i) {
    // The prototype scene has no instance level: a hit is a valid triangle.
    hits->instance[i] = hits->triangle[i] >= 0 ? instance : -1;
  }
}

}  // namespace hoilcd
