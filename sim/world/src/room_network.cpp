#include "hoilcd/sim/world/room_network.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "hoilcd/core/util/parallel.h"
#include "hoilcd/core/util/random.h"

namespace hoilcd {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
// How far a point may lie off a quad's plane and still be on it (windows sit 2 mm inside walls).
constexpr float kOnPlaneM = 1e-3f;
// The sun's lit shares are cast at every kSunStepS of the sequence's clock and linear between:
// the sun moves 3.75° in that time.
constexpr double kSunStepS = 900;
// Points per node at which the sun's lit share is taken.
constexpr int kSunSamples = 16;

// Which outside wall a room quad belongs to by its inward normal: 0 south (y = 0), 1 north, 2 west
// (x = 0), 3 east; -1 for a floor, a ceiling or anything not axis-aligned.
int WallOfNormal(const Eigen::Vector3f& n) {
  if (n.y() > 0.99f) return 0;
  if (n.y() < -0.99f) return 1;
  if (n.x() > 0.99f) return 2;
  if (n.x() < -0.99f) return 3;
  return -1;
}

float TriangleArea(const Eigen::Vector3f& a, const Eigen::Vector3f& b, const Eigen::Vector3f& c) {
  return 0.5f * (b - a).cross(c - a).norm();
}

// What every patch of one room quad shares: its material's emissivity, the convection and heat
// capacity of its kind of surface, and the U-value of the envelope behind it (0: none).
struct QuadThermals {
  double emissivity = 0.9, convection_w_m2k = 0, capacity_j_m2k = 0, u_value_w_m2k = 0;
};

QuadThermals ThermalsOfQuad(const RoomQuad& quad, const RoomOptions& room, const ThermalSolutionOptions& options,
                            const std::vector<InstanceMaterial>& room_materials,
                            const std::array<bool, 4>& exterior_walls) {
  const bool floor = quad.material == 0, ceiling = quad.material == 1;
  const bool window = quad.material >= 3 && quad.material < 3 + static_cast<int>(room.windows.size());
  const int wall = WallOfNormal(quad.normal);
  QuadThermals q;
  q.emissivity = room_materials[static_cast<size_t>(quad.material)].emissivity;
  // Outside walls (and every window) lose heat through the envelope.
  if (window) {
    q.u_value_w_m2k = room.windows[static_cast<size_t>(quad.material - 3)].u_value_w_m2k;
  } else if (quad.material == 2 && wall >= 0 && exterior_walls[static_cast<size_t>(wall)]) {
    q.u_value_w_m2k = room.surfaces.wall_u_value_w_m2k;
  }
  q.convection_w_m2k = floor     ? options.convection_floor_w_m2k
                       : ceiling ? options.convection_ceiling_w_m2k
                                 : options.convection_wall_w_m2k;
  q.capacity_j_m2k = floor     ? options.capacity_floor_j_m2k
                     : ceiling ? options.capacity_ceiling_j_m2k
                     : window  ? options.capacity_glass_j_m2k
                               : options.capacity_wall_j_m2k;
  return q;
}

// The node of the patch spanned by du and dv from corner a.
ThermalNode PatchNode(const QuadThermals& q, const Eigen::Vector3f& a, const Eigen::Vector3f& du,
                      const Eigen::Vector3f& dv) {
  ThermalNode node;
  node.area_m2 = du.cross(dv).norm();
  node.emissivity = q.emissivity;
  node.convection_w_m2k = q.convection_w_m2k;
  node.heat_capacity_j_k = q.capacity_j_m2k * node.area_m2;
  node.height_m = (a + 0.5f * du + 0.5f * dv).z();
  // From the inner surface to outdoor air the conductance is 1 / (1/U − R_si) per m².
  if (q.u_value_w_m2k > 0)
    node.outdoor_conductance_w_k = node.area_m2 / (1.0 / q.u_value_w_m2k - kInsideSurfaceResistance);
  return node;
}

// The room's quads as one mesh (triangles 2q and 2q + 1 are quad q).
TriangleMesh MeshOfQuads(const std::vector<RoomQuad>& quads) {
  TriangleMesh mesh;
  for (const RoomQuad& quad : quads) {
    const auto base = static_cast<uint32_t>(mesh.positions_m.size());
    for (const Eigen::Vector3f& c : quad.corners) mesh.positions_m.push_back(c);
    for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) mesh.indices.push_back(base + i);
    mesh.triangle_material.push_back(static_cast<uint32_t>(quad.material));
    mesh.triangle_material.push_back(static_cast<uint32_t>(quad.material));
  }
  return mesh;
}

// An instance's triangles in the world frame, per material (degenerate ones left out).
std::vector<std::vector<ThermalTriangle>> WorldTrianglesByMaterial(const InstanceInfo& info,
                                                                   const Eigen::Matrix4f& world_from_object) {
  const Eigen::Matrix3f rotation = world_from_object.topLeftCorner<3, 3>();
  const Eigen::Vector3f translation = world_from_object.topRightCorner<3, 1>();
  std::vector<std::vector<ThermalTriangle>> by_material(info.materials.size());
  const TriangleMesh& mesh = *info.mesh;
  for (size_t t = 0; t < mesh.TriangleCount(); ++t) {
    std::array<Eigen::Vector3f, 3> c;
    for (int k = 0; k < 3; ++k)
      c[static_cast<size_t>(k)] =
          rotation * mesh.positions_m[mesh.indices[3 * t + static_cast<size_t>(k)]] + translation;
    const Eigen::Vector3f n = (c[1] - c[0]).cross(c[2] - c[0]);
    if (n.squaredNorm() <= 0) continue;
    by_material[mesh.triangle_material[t]].push_back(ThermalTriangle{c, n.normalized()});
  }
  return by_material;
}

// The node of one material of a fixture, from its world triangles. A part with a power of its own,
// or declared at room temperature (none), is solved; one declared warmer or colder without a power
// (a radiator's water, a cooling jet) is held there.
ThermalNode FixtureNode(const std::vector<ThermalTriangle>& triangles, const InstanceMaterial& m, double power_w,
                        const ThermalSolutionOptions& options) {
  ThermalNode node;
  double area = 0, height = 0;
  for (const ThermalTriangle& t : triangles) {
    const double a = TriangleArea(t.corners[0], t.corners[1], t.corners[2]);
    area += a;
    height += a * (t.corners[0].z() + t.corners[1].z() + t.corners[2].z()) / 3.0;
  }
  node.area_m2 = area;
  node.height_m = height / area;
  node.emissivity = m.emissivity;
  node.convection_w_m2k = options.convection_object_w_m2k;
  node.heat_capacity_j_k = options.capacity_object_j_m2k * area;
  node.power_w = power_w;
  node.fixed = node.power_w == 0 && std::abs(m.temperature_c - kDeclaredRoomTemperatureC) > 1e-6;
  node.fixed_temperature_c = m.temperature_c;
  return node;
}

}  // namespace

struct RoomNetwork::Patches {
  Eigen::Vector3f origin, u_axis, v_axis;  // corner a, b − a, d − a
  int nu = 1, nv = 1;
  int first_node = 0;
  int Node(int iu, int iv) const { return first_node + iv * nu + iu; }
  // The quad's (u, v) in [0, 1]² of a world point, when it lies on the quad.
  bool Locate(const Eigen::Vector3f& p, const Eigen::Vector3f& normal, float* u, float* v) const {
    const Eigen::Vector3f d = p - origin;
    if (std::abs(d.dot(normal)) > kOnPlaneM) return false;
    *u = d.dot(u_axis) / u_axis.squaredNorm();
    *v = d.dot(v_axis) / v_axis.squaredNorm();
    constexpr float kSlack = 1e-4f;
    return *u >= -kSlack && *u <= 1 + kSlack && *v >= -kSlack && *v <= 1 + kSlack;
  }
};

RoomNetwork::RoomNetwork(const RoomOptions& room, const ThermalSolutionOptions& options, uint64_t seed,
                         const RoomClimate& climate, const std::vector<RoomQuad>& quads,
                         const std::vector<InstanceInfo>& instances, int room_instance,
                         const std::array<bool, 4>& exterior_walls, const BandRadianceTable& table, int threads)
    : table_(table),
      room_height_m_(room.size_m.z()),
      quads_(quads),
      options_(options),
      seed_(seed),
      room_instance_(room_instance) {
  std::vector<ThermalNode> nodes;
  std::vector<std::vector<ThermalTriangle>> triangles;
  const std::vector<InstanceMaterial>& room_materials = instances[static_cast<size_t>(room_instance)].materials;
  quads_of_material_.resize(room_materials.size());
  // Room patches: each quad cut into cells of about patch_size_m.
  for (size_t q = 0; q < quads_.size(); ++q) {
    const RoomQuad& quad = quads_[q];
    Patches p;
    p.origin = quad.corners[0];
    p.u_axis = quad.corners[1] - quad.corners[0];
    p.v_axis = quad.corners[3] - quad.corners[0];
    p.nu = std::max(1, static_cast<int>(std::lround(p.u_axis.norm() / options.patch_size_m)));
    p.nv = std::max(1, static_cast<int>(std::lround(p.v_axis.norm() / options.patch_size_m)));
    p.first_node = static_cast<int>(nodes.size());
    quads_of_material_[static_cast<size_t>(quad.material)].push_back(static_cast<int>(q));
    const QuadThermals thermals = ThermalsOfQuad(quad, room, options, room_materials, exterior_walls);
    // The glass transmits the sun (its own absorption is left out); interior walls are walls.
    const bool window = quad.material >= 3 && quad.material < 3 + static_cast<int>(room.windows.size());
    const Eigen::Vector3f du = p.u_axis / static_cast<float>(p.nu), dv = p.v_axis / static_cast<float>(p.nv);
    for (int iv = 0; iv < p.nv; ++iv) {
      for (int iu = 0; iu < p.nu; ++iu) {
        const Eigen::Vector3f a =
            p.origin + (static_cast<float>(iu) / p.nu) * p.u_axis + (static_cast<float>(iv) / p.nv) * p.v_axis;
        nodes.push_back(PatchNode(thermals, a, du, dv));
        solar_absorptance_.push_back(static_cast<float>(quad.material == 0 ? options.solar_absorptance_floor
                                                        : window           ? 0.0
                                                                           : options.solar_absorptance_walls));
        triangles.push_back({ThermalTriangle{{a, a + du, a + du + dv}, quad.normal},
                             ThermalTriangle{{a, a + du + dv, a + dv}, quad.normal}});
      }
    }
    patches_.push_back(p);
  }
  // Furniture and objects: a node per material of each instance that stands still.
  node_of_material_.resize(instances.size());
  mesh_of_.resize(instances.size(), nullptr);
  caster_ = std::make_unique<RayCaster>();
  RayCaster& caster = *caster_;
  std::map<const TriangleMesh*, int> prototypes;
  std::vector<int> world_instance_of{room_instance};
  caster.AddInstance(caster.AddPrototype(MeshOfQuads(quads_)), Eigen::Matrix4f::Identity());
  for (size_t w = 0; w < instances.size(); ++w) {
    const InstanceInfo& info = instances[w];
    if (!info.fixture || info.mesh == nullptr) continue;
    const Eigen::Matrix4f world_from_object = info.object_from_world.inverse();
    std::vector<std::vector<ThermalTriangle>> by_material = WorldTrianglesByMaterial(info, world_from_object);
    node_of_material_[w].assign(info.materials.size(), -1);
    mesh_of_[w] = info.mesh;
    for (size_t k = 0; k < info.materials.size(); ++k) {
      if (by_material[k].empty()) continue;
      const double power_w = info.asset != nullptr ? info.asset->materials[k].power_w : 0.0;
      node_of_material_[w][k] = static_cast<int>(nodes.size());
      nodes.push_back(FixtureNode(by_material[k], info.materials[k], power_w, options));
      solar_absorptance_.push_back(static_cast<float>(options.solar_absorptance_object));
      triangles.push_back(std::move(by_material[k]));
    }
    auto [it, inserted] = prototypes.emplace(info.mesh, -1);
    if (inserted) it->second = caster.AddPrototype(*info.mesh);
    caster.AddInstance(it->second, world_from_object);
    world_instance_of.push_back(static_cast<int>(w));
  }
  caster.Commit();
  node_area_.reserve(nodes.size());
  for (const ThermalNode& n : nodes) node_area_.push_back(static_cast<float>(n.area_m2));
  nodes_ = std::move(nodes);
  world_instance_of_ = std::move(world_instance_of);
  threads_ = threads;
  triangles_ = std::move(triangles);
  const RoomClimate air = climate;
  const double gradient = options.air_gradient_k_per_m, mid_height = 0.5 * room_height_m_;
  drivers_.air_c = [air, gradient, mid_height](double time_s, double height_m) {
    return air.AirTemperatureC(time_s) + gradient * (height_m - mid_height);
  };
  drivers_.outdoor_c = room.outdoor_temperature_c;
  sun_ = room.sun;
  sun_can_enter_ = room.sun.enabled && !room.windows.empty();
  frame_width_m_ = room.surfaces.window_frames ? room.surfaces.frame_width_m : 0.0;
  window_count_ = static_cast<int>(room.windows.size());
  drivers_.absorbed = [this](double time_s, std::vector<double>* absorbed_w) {
    PeopleHeat(time_s, absorbed_w);
    SolarHeat(time_s, absorbed_w);
  };
  room_mean_c_.assign(room_materials.size(), kNaN);
  room_incident_.assign(room_materials.size(), kNaN);
}

RoomNetwork::~RoomNetwork() = default;

int RoomNetwork::NodeOfHit(const RayHit& hit, const Eigen::Vector3f& point) const {
  if (hit.instance == room_instance_) {
    const auto q = static_cast<size_t>(hit.triangle / 2);
    const Patches& p = patches_[q];
    const Eigen::Vector3f d = point - p.origin;
    const float u = d.dot(p.u_axis) / p.u_axis.squaredNorm(), v = d.dot(p.v_axis) / p.v_axis.squaredNorm();
    const int iu = std::clamp(static_cast<int>(u * static_cast<float>(p.nu)), 0, p.nu - 1);
    const int iv = std::clamp(static_cast<int>(v * static_cast<float>(p.nv)), 0, p.nv - 1);
    return p.Node(iu, iv);
  }
  const auto w = static_cast<size_t>(hit.instance);
  if (node_of_material_[w].empty()) return -1;
  return node_of_material_[w][mesh_of_[w]->triangle_material[static_cast<size_t>(hit.triangle)]];
}

void RoomNetwork::SetPeople(const std::vector<PersonSource>& people) {
  people_ = people;
  person_coupling_.assign(people_.size(), {});
  constexpr int kSamples = 16;     // points per node at which a person's view factor is taken
  constexpr float kReachM = 2.5f;  // beyond, a person's view factor is under 2 % of a node's view
  for (size_t p = 0; p < people_.size(); ++p) {
    const PersonSource& person = people_[p];
    const auto radius = static_cast<float>(person.radius_m);
    for (size_t i = 0; i < triangles_.size(); ++i) {
      const std::vector<ThermalTriangle>& triangles = triangles_[i];
      if (triangles.empty()) continue;
      // Point-to-sphere view factor (r/d)² cos θ, averaged over points spread over the node's
      // triangles (keyed, so the same every time), each blocked when the static geometry lies
      // between it and the sphere's centre.
      Rng rng = KeyedRng(seed_, "room.thermal.people", i);
      double sum = 0;
      bool near = false;
      for (int k = 0; k < kSamples; ++k) {
        const ThermalTriangle& t = triangles[rng.UniformInt(static_cast<uint32_t>(triangles.size()))];
        const Eigen::Vector3f point = UniformPointOn(t, &rng);
        const Eigen::Vector3f to = person.centre_m - point;
        const float d = to.norm();
        if (d > kReachM || d <= radius) continue;
        near = true;
        const float cos_theta = t.normal.dot(to) / d;
        if (cos_theta <= 0) continue;
        const Eigen::Vector3f origin = point + 1e-3f * t.normal;
        const RayHit hit = caster_->Intersect(origin, to / d, 0.0f, d - radius);
        if (hit.hit()) continue;
        sum += (radius / d) * (radius / d) * cos_theta;
      }
      if (!near || sum <= 0) continue;
      const ThermalNode& node = nodes_[i];
      person_coupling_[p].emplace_back(static_cast<int>(i),
                                       node.area_m2 * sum / kSamples * node.emissivity * person.emissivity);
    }
  }
  started_ = false;
}

void RoomNetwork::PeopleHeat(double time_s, std::vector<double>* absorbed_w) const {
  constexpr double kKelvin = 273.15;
  for (size_t p = 0; p < people_.size(); ++p) {
    const PersonSource& person = people_[p];
    const bool present = time_s < 0 ? (person.arrive_s <= 0 && person.leave_s > 0)
                                    : (person.arrive_s <= time_s && time_s < person.leave_s);
    if (!present) continue;
    const double tp = person.surface_c + kKelvin;
    for (const auto& [i, coupling] : person_coupling_[p]) {
      // The node's own emission towards the sphere is taken at the air by it: the exchange is
      // a few watts, and the node's departure from the air changes it by a few per cent.
      const double tn = drivers_.air_c(time_s, nodes_[static_cast<size_t>(i)].height_m) + kKelvin;
      (*absorbed_w)[static_cast<size_t>(i)] += coupling * kStefanBoltzmann * (tp * tp * tp * tp - tn * tn * tn * tn);
    }
  }
}

bool RoomNetwork::SunlitThroughWindow(const Eigen::Vector3f& p, const Eigen::Vector3f& n,
                                      const Eigen::Vector3f& sun) const {
  const Eigen::Vector3f origin = p + 1e-3f * n;
  const RayHit hit = caster_->Intersect(origin, sun);
  if (!hit.hit() || world_instance_of_[static_cast<size_t>(hit.instance)] != room_instance_) return false;
  const auto q = static_cast<size_t>(hit.triangle / 2);
  const RoomQuad& quad = quads_[q];
  if (quad.material < 3 || quad.material >= 3 + window_count_) return false;
  const Patches& glass = patches_[q];
  float u = 0, v = 0;
  if (!glass.Locate(origin + hit.distance_m * sun, quad.normal, &u, &v)) return false;
  const float to_edge = std::min(std::min(u, 1 - u) * glass.u_axis.norm(), std::min(v, 1 - v) * glass.v_axis.norm());
  return to_edge >= static_cast<float>(frame_width_m_);
}

const std::vector<float>& RoomNetwork::SunSharesOfKey(int64_t key) {
  // Time moves forwards: grid times two steps back are not asked again.
  while (!sun_shares_of_key_.empty() && sun_shares_of_key_.begin()->first + 1 < key) {
    sun_shares_of_key_.erase(sun_shares_of_key_.begin());
  }
  auto it = sun_shares_of_key_.find(key);
  if (it != sun_shares_of_key_.end()) return it->second;
  std::vector<float> shares(nodes_.size(), 0.0f);
  const SunInRoom sun = SunAt(sun_, static_cast<double>(key) * kSunStepS);
  if (sun.irradiance_wm2 > 0) {
    ParallelFor(static_cast<int64_t>(nodes_.size()), threads_, [&](int64_t i) {
      const std::vector<ThermalTriangle>& triangles = triangles_[static_cast<size_t>(i)];
      if (triangles.empty() || solar_absorptance_[static_cast<size_t>(i)] <= 0) return;
      // Keyed points spread over the node's triangles by area, so the same at any thread count.
      const AreaSampler sampler(triangles);
      Rng rng = KeyedRng(seed_, "room.thermal.sun", static_cast<uint64_t>(i));
      double sum = 0;
      for (int k = 0; k < kSunSamples; ++k) {
        Eigen::Vector3f point;
        const ThermalTriangle& t = sampler.Draw(&rng, &point);
        const float cos_incidence = t.normal.dot(sun.direction);
        if (cos_incidence <= 0) continue;
        if (SunlitThroughWindow(point, t.normal, sun.direction)) sum += cos_incidence;
      }
      shares[static_cast<size_t>(i)] = static_cast<float>(sum / kSunSamples);
    });
  }
  return sun_shares_of_key_.emplace(key, std::move(shares)).first->second;
}

std::vector<float> RoomNetwork::SunShares(double time_s) {
  if (!sun_can_enter_) return {};
  const double at = time_s / kSunStepS;
  const auto key = static_cast<int64_t>(std::floor(at));
  const auto w = static_cast<float>(at - static_cast<double>(key));
  const std::vector<float>& a = SunSharesOfKey(key);  // kept: the next call erases only older keys
  const std::vector<float>& b = SunSharesOfKey(key + 1);
  std::vector<float> shares(a.size());
  for (size_t i = 0; i < a.size(); ++i) shares[i] = (1 - w) * a[i] + w * b[i];
  return shares;
}

void RoomNetwork::SolarHeat(double time_s, std::vector<double>* absorbed_w) {
  if (!sun_can_enter_) return;
  const SunInRoom sun = SunAt(sun_, time_s);
  if (sun.irradiance_wm2 <= 0) return;
  const std::vector<float> shares = SunShares(time_s);
  for (size_t i = 0; i < shares.size(); ++i) {
    (*absorbed_w)[i] += static_cast<double>(solar_absorptance_[i]) * nodes_[i].area_m2 * sun.irradiance_wm2 * shares[i];
  }
}

void RoomNetwork::CastViewFactorsOnce() {
  if (network_ != nullptr) return;
  std::vector<double> areas;
  for (const ThermalNode& n : nodes_) areas.push_back(n.area_m2);
  const ViewFactors view_factors = CastViewFactors(
      *caster_, triangles_, areas,
      [&](const RayHit& hit, const Eigen::Vector3f& point) {
        RayHit in_world = hit;
        in_world.instance = world_instance_of_[static_cast<size_t>(hit.instance)];
        return NodeOfHit(in_world, point);
      },
      options_.rays_per_node, HashCombine(seed_, HashString("room.thermal.view_factors")), threads_);
  network_ = std::make_unique<ThermalNetwork>(nodes_, view_factors, threads_);
}

void RoomNetwork::SetTime(double time_s) {
  CastViewFactorsOnce();
  if (!started_) {
    network_->Start(drivers_, 0.0, options_.step_s, options_.spin_up_s);
    incident_of_state_.clear();
    started_ = true;
  }
  network_->AdvanceTo(time_s);
  network_->TemperaturesAt(time_s, &temperature_c_);
  // What each node receives, linear between the grid states' (each solved once).
  size_t k = 0;
  double w = 0;
  network_->GridPlace(time_s, &k, &w);
  const size_t k1 = std::min(k + 1, network_->grid_size() - 1);
  const std::vector<float>& a = IncidentOfState(k);
  const std::vector<float>& b = IncidentOfState(k1);
  const size_t n = temperature_c_.size();
  incident_.resize(n);
  for (size_t i = 0; i < n; ++i) incident_[i] = static_cast<float>((1 - w) * a[i] + w * b[i]);
  double sum = 0, area = 0;
  for (size_t i = 0; i < n; ++i) {
    sum += static_cast<double>(incident_[i]) * node_area_[i];
    area += node_area_[i];
  }
  mean_incident_ = static_cast<float>(sum / std::max(area, 1e-12));
  sun_share_ = SunShares(time_s);
  for (size_t m = 0; m < quads_of_material_.size(); ++m) {
    double t_sum = 0, l_sum = 0, a_sum = 0;
    for (int q : quads_of_material_[m]) {
      const Patches& p = patches_[static_cast<size_t>(q)];
      for (int i = p.first_node; i < p.first_node + p.nu * p.nv; ++i) {
        const auto node = static_cast<size_t>(i);
        t_sum += temperature_c_[node] * node_area_[node];
        l_sum += static_cast<double>(incident_[node]) * node_area_[node];
        a_sum += node_area_[node];
      }
    }
    room_mean_c_[m] = a_sum > 0 ? static_cast<float>(t_sum / a_sum) : kNaN;
    room_incident_[m] = a_sum > 0 ? static_cast<float>(l_sum / a_sum) : kNaN;
  }
}

const std::vector<float>& RoomNetwork::IncidentOfState(size_t k) {
  // Frames move forwards: states before the earliest one asked are not asked again.
  while (!incident_of_state_.empty() && incident_of_state_.begin()->first + 1 < k) {
    incident_of_state_.erase(incident_of_state_.begin());
  }
  auto it = incident_of_state_.find(k);
  if (it != incident_of_state_.end()) return it->second;
  const std::vector<double>& state = network_->GridState(k);
  const size_t n = state.size();
  std::vector<float> emitted(n), reflectivity(n);
  for (size_t i = 0; i < n; ++i) {
    const auto emissivity = static_cast<float>(nodes_[i].emissivity);
    emitted[i] = emissivity * table_.RadianceFromCelsius(static_cast<float>(state[i]));
    reflectivity[i] = 1 - emissivity;
  }
  const double time_s = network_->GridTime(k);
  const auto open = table_.RadianceFromCelsius(static_cast<float>(drivers_.air_c(time_s, 0.5 * room_height_m_)));
  return incident_of_state_.emplace(k, network_->IncidentRadiance(emitted, reflectivity, open)).first->second;
}

float RoomNetwork::RoomTemperatureC(int material, const Eigen::Vector3f& p) const {
  PatchState state;
  return RoomSurfaceAt(material, p, &state) ? state.temperature_c : kNaN;
}

bool RoomNetwork::RoomSurfaceAt(int material, const Eigen::Vector3f& p, PatchState* state) const {
  if (material < 0 || material >= static_cast<int>(quads_of_material_.size())) return false;
  for (int q : quads_of_material_[static_cast<size_t>(material)]) {
    const Patches& patches = patches_[static_cast<size_t>(q)];
    float u = 0, v = 0;
    if (!patches.Locate(p, quads_[static_cast<size_t>(q)].normal, &u, &v)) continue;
    // Bilinear between the centres of the four nearest patches (clamped at the quad's edges).
    const float fu = std::clamp(u * static_cast<float>(patches.nu) - 0.5f, 0.0f, static_cast<float>(patches.nu - 1));
    const float fv = std::clamp(v * static_cast<float>(patches.nv) - 0.5f, 0.0f, static_cast<float>(patches.nv - 1));
    const int u0 = static_cast<int>(fu), v0 = static_cast<int>(fv);
    const int u1 = std::min(u0 + 1, patches.nu - 1), v1 = std::min(v0 + 1, patches.nv - 1);
    const float wu = fu - static_cast<float>(u0), wv = fv - static_cast<float>(v0);
    auto bilinear = [&](auto&& at) {
      return (1 - wv) * ((1 - wu) * at(u0, v0) + wu * at(u1, v0)) + wv * ((1 - wu) * at(u0, v1) + wu * at(u1, v1));
    };
    auto node = [&](int iu, int iv) { return static_cast<size_t>(patches.Node(iu, iv)); };
    state->temperature_c = bilinear([&](int iu, int iv) { return static_cast<float>(temperature_c_[node(iu, iv)]); });
    state->incident = bilinear([&](int iu, int iv) { return incident_[node(iu, iv)]; });
    state->sun_share = sun_share_.empty() ? 0.0f : bilinear([&](int iu, int iv) { return sun_share_[node(iu, iv)]; });
    return true;
  }
  return false;
}

float RoomNetwork::RoomMeanTemperatureC(int material) const {
  if (material < 0 || material >= static_cast<int>(room_mean_c_.size())) return kNaN;
  return room_mean_c_[static_cast<size_t>(material)];
}

float RoomNetwork::RoomMeanIncidentRadiance(int material) const {
  if (material < 0 || material >= static_cast<int>(room_incident_.size())) return kNaN;
  return room_incident_[static_cast<size_t>(material)];
}

float RoomNetwork::InstanceTemperatureC(int instance, int material) const {
  const int node = NodeOf(instance, material);
  if (node < 0 || nodes_[static_cast<size_t>(node)].fixed) return kNaN;
  return static_cast<float>(temperature_c_[static_cast<size_t>(node)]);
}

float RoomNetwork::IncidentRadiance(int instance, int material) const {
  if (instance == room_instance_) return RoomMeanIncidentRadiance(material);
  const int node = NodeOf(instance, material);
  return node < 0 ? kNaN : incident_[static_cast<size_t>(node)];
}

int RoomNetwork::NodeOf(int instance, int material) const {
  if (instance < 0 || instance >= static_cast<int>(node_of_material_.size())) return -1;
  const auto& materials = node_of_material_[static_cast<size_t>(instance)];
  if (material < 0 || material >= static_cast<int>(materials.size())) return -1;
  return materials[static_cast<size_t>(material)];
}

}  // namespace hoilcd
