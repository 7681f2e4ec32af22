#include "hoilcd/sim/world/room_thermal.h"

#include <algorithm>
#include <cmath>

#include "hoilcd/core/util/random.h"
#include "hoilcd/sim/scene/building_floor.h"
#include "hoilcd/sim/world/room_network.h"

namespace hoilcd {
namespace {

constexpr double kDegToRad = M_PI / 180.0;
// A 3-D corner (two walls and the ceiling or floor) is colder than a 2-D edge, but not by the sum
// of its three edges: the summed edge cooling is capped at this multiple of one edge's.
constexpr float kCornerCap = 1.5f;
// The sun's disc is 0.53° across: a patch's edge blurs by this much per metre from the window.
constexpr float kPenumbraPerM = 0.0093f;
constexpr float kSharpestEdgeM = 0.01f;

int WallIndex(const std::string& wall) {
  if (wall == "south") return 0;
  if (wall == "north") return 1;
  if (wall == "west") return 2;
  return 3;
}

// Position along wall `wall` (x on south/north, y on west/east).
float AlongWall(int wall, const Eigen::Vector3f& p) { return wall < 2 ? p.x() : p.y(); }

// How far p (along, z) is inside a window's rectangle shrunk by `inset` (negative: outside).
float InsideWindowM(const WindowSpec& w, float along, float z, float inset) {
  const auto a0 = static_cast<float>(w.center_m - 0.5 * w.width_m) + inset;
  const auto a1 = static_cast<float>(w.center_m + 0.5 * w.width_m) - inset;
  const auto z0 = static_cast<float>(w.bottom_m) + inset, z1 = static_cast<float>(w.bottom_m + w.height_m) - inset;
  return std::min({along - a0, a1 - along, z - z0, z1 - z});
}

}  // namespace

double InsideSurfaceTemperatureC(double u_value_w_m2k, double t_in_c, double t_out_c) {
  return t_in_c - u_value_w_m2k * kInsideSurfaceResistance * (t_in_c - t_out_c);
}

SunPosition SolarPosition(double latitude_deg, int day_of_year, double solar_hour) {
  const double declination = 23.45 * kDegToRad * std::sin(2 * M_PI * (284 + day_of_year) / 365.0);
  const double hour_angle = 15 * kDegToRad * (solar_hour - 12);
  const double phi = latitude_deg * kDegToRad;
  const double sin_elevation =
      std::sin(phi) * std::sin(declination) + std::cos(phi) * std::cos(declination) * std::cos(hour_angle);
  SunPosition sun;
  sun.elevation_rad = std::asin(std::clamp(sin_elevation, -1.0, 1.0));
  const double denominator = std::cos(sun.elevation_rad) * std::cos(phi);
  const double cos_azimuth =
      denominator > 1e-9 ? (std::sin(declination) - sin_elevation * std::sin(phi)) / denominator : 1.0;
  sun.azimuth_rad = std::acos(std::clamp(cos_azimuth, -1.0, 1.0));
  if (hour_angle > 0) sun.azimuth_rad = 2 * M_PI - sun.azimuth_rad;  // afternoon: west of south
  return sun;
}

SunInRoom SunAt(const SunOptions& sun, double time_s) {
  SunInRoom in_room;
  if (!sun.enabled) return in_room;
  const double hour = std::fmod(sun.time_of_day_h + time_s / 3600.0, 24.0);
  const SunPosition at = SolarPosition(sun.latitude_deg, sun.day_of_year, hour);
  const double east = std::sin(at.azimuth_rad) * std::cos(at.elevation_rad);
  const double north = std::cos(at.azimuth_rad) * std::cos(at.elevation_rad);
  const double y_axis = sun.north_wall_azimuth_deg * kDegToRad;
  in_room.direction = Eigen::Vector3d(east * std::cos(y_axis) - north * std::sin(y_axis),
                                      east * std::sin(y_axis) + north * std::cos(y_axis), std::sin(at.elevation_rad))
                          .cast<float>();
  in_room.irradiance_wm2 = static_cast<float>(ClearSkyDirectNormalWm2(at.elevation_rad) * sun.glass_transmittance);
  return in_room;
}

double ClearSkyDirectNormalWm2(double elevation_rad) {
  if (elevation_rad <= 0) return 0;
  const double elevation_deg = elevation_rad / kDegToRad;
  const double air_mass = 1.0 / (std::sin(elevation_rad) + 0.50572 * std::pow(elevation_deg + 6.07995, -1.6364));
  return 1353.0 * std::pow(0.7, std::pow(air_mass, 0.678));
}

std::vector<Eigen::AlignedBox3f> RadiatorBoxes(const std::vector<InstanceInfo>& instances, int radiator_class) {
  std::vector<Eigen::AlignedBox3f> boxes;
  for (const InstanceInfo& info : instances) {
    if (info.class_id != radiator_class || info.asset == nullptr) continue;
    const Eigen::Matrix4f world_from_object = info.object_from_world.inverse();
    Eigen::AlignedBox3f box;
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3f p = info.asset->bounds_m.corner(static_cast<Eigen::AlignedBox3f::CornerType>(corner));
      box.extend(world_from_object.topLeftCorner<3, 3>() * p + world_from_object.topRightCorner<3, 1>());
    }
    boxes.push_back(box);
  }
  return boxes;
}

RoomClimate::RoomClimate(const RoomOptions& room, uint64_t seed, double clock_offset_s)
    : hvac_(room.hvac), mean_c_(room.environment_temperature_c) {
  phase_s_ = KeyedRng(seed, "room.hvac.phase").Uniform() * hvac_.period_s + clock_offset_s;
  // Periodic steady state of y' = (u − y)/τ for the triangle u: the lagged value y0 at the start
  // of a heating phase maps to y1 at its end and back to y0 after the cooling phase.
  const double b = hvac_.deadband_k, tau = hvac_.surface_lag_s;
  const double t1 = hvac_.heating_fraction * hvac_.period_s, t2 = hvac_.period_s - t1;
  const double k1 = b / t1, k2 = -b / t2;
  const double e1 = std::exp(-t1 / tau), e2 = std::exp(-t2 / tau);
  const double a1 = b / 2 - k1 * tau + (b / 2 + k1 * tau) * e1;
  const double a2 = -b / 2 - k2 * tau + (-b / 2 + k2 * tau) * e2;
  lag_start_k_ = tau > 0 ? (a2 + e2 * a1) / (1 - e1 * e2) : -b / 2;
}

double RoomClimate::CycleTimeS(double time_s) const {
  const double u = std::fmod(time_s + phase_s_, hvac_.period_s);
  return u < 0 ? u + hvac_.period_s : u;
}

double RoomClimate::AirOffsetK(double time_s) const {
  if (!hvac_.enabled) return 0;
  const double b = hvac_.deadband_k, p = hvac_.period_s;
  const double t1 = hvac_.heating_fraction * p;
  const double u = CycleTimeS(time_s);
  return u < t1 ? -b / 2 + b * u / t1 : b / 2 - b * (u - t1) / (p - t1);
}

double RoomClimate::AirTemperatureC(double time_s) const { return mean_c_ + AirOffsetK(time_s); }

double RoomClimate::SurfaceOffsetK(double time_s) const {
  if (!hvac_.enabled) return 0;
  const double tau = hvac_.surface_lag_s;
  if (tau <= 0) return AirOffsetK(time_s);
  const double b = hvac_.deadband_k, p = hvac_.period_s;
  const double t1 = hvac_.heating_fraction * p;
  const double u = CycleTimeS(time_s);
  const double air = AirOffsetK(time_s);
  const double k1 = b / t1, k2 = -b / (p - t1);
  if (u < t1) return air - k1 * tau + (lag_start_k_ + b / 2 + k1 * tau) * std::exp(-u / tau);
  const double y1 = b / 2 - k1 * tau + (lag_start_k_ + b / 2 + k1 * tau) * std::exp(-t1 / tau);
  return air - k2 * tau + (y1 - b / 2 + k2 * tau) * std::exp(-(u - t1) / tau);
}

// The field of one room material: the owner's offset at the hit's world point (room frame =
// world frame).
class RoomSurfaces::Field : public SurfaceField {
 public:
  Field(const RoomSurfaces* owner, int material) : owner_(owner), material_(material) {}
  float OffsetK(const Eigen::Vector3f& /*object_point*/, const Eigen::Vector3f& world_point) const override {
    return owner_->OffsetK(material_, world_point);
  }
  FieldSample Sample(const Eigen::Vector3f& /*object_point*/, const Eigen::Vector3f& world_point) const override {
    return owner_->Sample(material_, world_point);
  }

 private:
  const RoomSurfaces* owner_;
  int material_;
};

RoomSurfaces::RoomSurfaces(const RoomOptions& room, uint64_t seed, const std::vector<Eigen::AlignedBox3f>& radiators,
                           const std::vector<Eigen::AlignedBox2f>& interior_walls, double clock_offset_s)
    : room_(room),
      seed_(seed),
      climate_(room, seed, clock_offset_s),
      size_m_(room.size_m.cast<float>()),
      interior_walls_(interior_walls) {
  const RoomSurfaceOptions& s = room_.surfaces;
  for (const WindowSpec& w : room_.windows) {
    if (s.exterior_walls == "windowed") exterior_[WallIndex(w.wall)] = true;
  }
  if (s.exterior_walls == "all") exterior_.fill(true);
  const bool any_exterior = std::find(exterior_.begin(), exterior_.end(), true) != exterior_.end();
  for (const Eigen::AlignedBox3f& box : radiators) {
    // The wall it stands against; a radiator further than 0.3 m from every wall warms none.
    const std::array<float, 4> gap = {box.min().y(), size_m_.y() - box.max().y(), box.min().x(),
                                      size_m_.x() - box.max().x()};
    const int wall = static_cast<int>(std::min_element(gap.begin(), gap.end()) - gap.begin());
    if (gap[wall] > 0.3f) continue;
    Radiator r;
    r.wall = wall;
    r.lo_m = wall < 2 ? box.min().x() : box.min().y();
    r.hi_m = wall < 2 ? box.max().x() : box.max().y();
    r.bottom_m = box.min().z();
    r.top_m = box.max().z();
    radiators_.push_back(r);
  }
  const bool bridges = s.thermal_bridges && any_exterior;
  const bool plume = s.radiator_plume && !radiators_.empty() && s.plume_warming_k > 0;
  const bool sun = room_.sun.enabled && !room_.windows.empty();
  const bool texture = s.texture && s.texture_k > 0;
  const int materials = 3 + static_cast<int>(room_.windows.size());
  if (!interior_walls_.empty()) interior_material_ = materials;
  fields_.resize(static_cast<size_t>(materials + (interior_walls_.empty() ? 0 : 1)));
  for (int k = 0; k < materials; ++k) {
    const bool on = k < 3 ? (bridges || sun || texture || (k == 2 && plume)) : (s.window_frames && s.frame_width_m > 0);
    if (on) fields_[static_cast<size_t>(k)] = std::make_unique<Field>(this, k);
  }
  if (interior_material_ >= 0 && texture) fields_.back() = std::make_unique<Field>(this, interior_material_);
  frame_minus_glass_k_.assign(room_.windows.size(), 0.0f);
}

RoomSurfaces::~RoomSurfaces() = default;

void RoomSurfaces::AttachNetwork(const RoomNetwork* network) {
  network_ = network;
  for (size_t k = 0; k < fields_.size(); ++k) {
    if (fields_[k] == nullptr) fields_[k] = std::make_unique<Field>(this, static_cast<int>(k));
  }
}

const SurfaceField* RoomSurfaces::FieldOf(int material) const {
  if (material < 0 || material >= static_cast<int>(fields_.size())) return nullptr;
  return fields_[static_cast<size_t>(material)].get();
}

double RoomSurfaces::EnvironmentTemperatureC(double time_s) const {
  return room_.environment_temperature_c + climate_.SurfaceOffsetK(time_s);
}

void RoomSurfaces::SetTime(double time_s, std::vector<InstanceMaterial>* materials) {
  const RoomSurfaceOptions& s = room_.surfaces;
  const auto offset = static_cast<float>(climate_.SurfaceOffsetK(time_s));
  // The inside temperature the surfaces see: the air as the surfaces have followed it.
  const double inside_c = EnvironmentTemperatureC(time_s), outside_c = room_.outdoor_temperature_c;
  auto set = [&](int k, double bottom_c, double top_c) {
    InstanceMaterial& m = (*materials)[static_cast<size_t>(k)];
    m.temperature_c = static_cast<float>(bottom_c);
    m.temperature_top_c = static_cast<float>(top_c);
    m.field = FieldOf(k);
  };
  const double frame_c = InsideSurfaceTemperatureC(s.frame_u_value_w_m2k, inside_c, outside_c);
  if (network_ != nullptr) {
    for (size_t k = 0; k < fields_.size(); ++k) {
      const float mean_c = network_->RoomMeanTemperatureC(static_cast<int>(k));
      set(static_cast<int>(k), mean_c, mean_c);
    }
  } else {
    set(0, room_.floor.temperature_c + offset, room_.floor.temperature_c + offset);
    set(1, room_.ceiling.temperature_c + offset, room_.ceiling.temperature_c + offset);
    set(2, room_.walls.temperature_bottom_c + offset, room_.walls.temperature_top_c + offset);
    if (interior_material_ >= 0) {
      set(interior_material_, room_.walls.temperature_bottom_c + offset, room_.walls.temperature_top_c + offset);
    }
  }
  for (size_t i = 0; i < room_.windows.size(); ++i) {
    const WindowSpec& w = room_.windows[i];
    const double glass_c = s.glass_from_u_value ? InsideSurfaceTemperatureC(w.u_value_w_m2k, inside_c, outside_c)
                                                : w.surface.temperature_c;
    if (network_ == nullptr) set(3 + static_cast<int>(i), glass_c, glass_c);
    frame_minus_glass_k_[i] = static_cast<float>(frame_c - glass_c);
  }
  const double wall_f = 1 - s.wall_u_value_w_m2k * kInsideSurfaceResistance;
  bridge_k_ = static_cast<float>(std::max(0.0, wall_f - s.edge_f_rsi) * (inside_c - outside_c));
  const SunInRoom sun = SunAt(room_.sun, time_s);
  sun_direction_ = sun.direction;
  sun_irradiance_wm2_ = sun.irradiance_wm2;
}

FieldSample RoomSurfaces::Sample(int material, const Eigen::Vector3f& p) const {
  if (FieldOf(material) == nullptr) return {};
  float solved = 0;     // the solution's patches about the material's mean (set as its base)
  float incident = 0;   // what they receive about the material's mean
  float sun_share = 0;  // the patches' sunlit share (the sun in their balance)
  RoomNetwork::PatchState patch;
  if (network_ != nullptr && network_->RoomSurfaceAt(material, p, &patch)) {
    solved = patch.temperature_c - network_->RoomMeanTemperatureC(material);
    incident = patch.incident - network_->RoomMeanIncidentRadiance(material);
    sun_share = patch.sun_share;
  }
  if (material == interior_material_) return {solved + TextureK(material, p), incident};
  if (material >= 3) return {solved + FrameK(material - 3, p), incident};
  // With the sun in the patches' balance, the closed form adds only the sunlit shape within them,
  // about their lit share, so that their heat is not counted twice.
  float sun = SunK(material, p);
  if (sun_share > 0)
    sun -= static_cast<float>(room_.sun.warming_k_per_kw_m2) * sun_irradiance_wm2_ * sun_share / 1000.0f;
  float offset = solved + BridgeK(material, p) + sun + TextureK(material, p);
  if (material == 2) offset += PlumeK(p);
  return {offset, incident};
}

int RoomSurfaces::WallAt(const Eigen::Vector3f& p) const {
  const std::array<float, 4> gap = {std::abs(p.y()), std::abs(size_m_.y() - p.y()), std::abs(p.x()),
                                    std::abs(size_m_.x() - p.x())};
  return static_cast<int>(std::min_element(gap.begin(), gap.end()) - gap.begin());
}

float RoomSurfaces::BridgeK(int material, const Eigen::Vector3f& p) const {
  if (!room_.surfaces.thermal_bridges || bridge_k_ <= 0) return 0;
  const float decay = static_cast<float>(room_.surfaces.bridge_decay_m);
  float sum = 0;
  auto edge = [&](bool bridged, float distance_m) {
    if (bridged) sum += std::exp(-std::max(distance_m, 0.0f) / decay);
  };
  // Distance to each wall: south, north, west, east.
  const std::array<float, 4> to_wall = {p.y(), size_m_.y() - p.y(), p.x(), size_m_.x() - p.x()};
  if (material < 2) {  // floor or ceiling: its edge along each outside wall
    for (int w = 0; w < 4; ++w) edge(exterior_[w], to_wall[w]);
  } else {
    const int w = WallAt(p);
    edge(exterior_[w], p.z());                                 // wall–floor
    edge(exterior_[w], size_m_.z() - p.z());                   // wall–ceiling
    const int side_a = w < 2 ? 2 : 0, side_b = w < 2 ? 3 : 1;  // the walls it meets
    edge(exterior_[w] || exterior_[side_a], to_wall[side_a]);
    edge(exterior_[w] || exterior_[side_b], to_wall[side_b]);
  }
  return -bridge_k_ * std::min(sum, kCornerCap);
}

float RoomSurfaces::PlumeK(const Eigen::Vector3f& p) const {
  if (!room_.surfaces.radiator_plume || radiators_.empty()) return 0;
  const RoomSurfaceOptions& s = room_.surfaces;
  const int wall = WallAt(p);
  float warming = 0;
  for (const Radiator& r : radiators_) {
    if (r.wall != wall || p.z() < r.bottom_m) continue;
    const float above = std::max(0.0f, p.z() - r.top_m);
    const float vertical = std::exp(-above / static_cast<float>(s.plume_height_m));
    const float sd = static_cast<float>(s.plume_spread_m) + 0.25f * above;
    const float along = AlongWall(wall, p);
    const float outside = std::max({r.lo_m - along, along - r.hi_m, 0.0f});
    warming += static_cast<float>(s.plume_warming_k) * vertical * std::exp(-0.5f * outside * outside / (sd * sd));
  }
  return warming;
}

float RoomSurfaces::SunK(int material, const Eigen::Vector3f& p) const {
  if (sun_irradiance_wm2_ <= 0) return 0;
  static const std::array<Eigen::Vector3f, 4> kWallNormal = {Eigen::Vector3f::UnitY(), -Eigen::Vector3f::UnitY(),
                                                             Eigen::Vector3f::UnitX(), -Eigen::Vector3f::UnitX()};
  const Eigen::Vector3f normal = material == 0   ? Eigen::Vector3f::UnitZ()
                                 : material == 1 ? Eigen::Vector3f(-Eigen::Vector3f::UnitZ())
                                                 : kWallNormal[WallAt(p)];
  const float cos_incidence = normal.dot(sun_direction_);
  if (cos_incidence <= 0) return 0;
  // Where the ray towards the sun leaves the (convex) room: sunlit if that is through a window.
  float travel = 1e30f;
  int exit_axis = 2;
  for (int axis = 0; axis < 3; ++axis) {
    const float d = sun_direction_[axis];
    if (std::abs(d) < 1e-9f) continue;
    const float s = d > 0 ? (size_m_[axis] - p[axis]) / d : -p[axis] / d;
    if (s < travel) {
      travel = s;
      exit_axis = axis;
    }
  }
  if (exit_axis == 2) return 0;  // through the ceiling
  const Eigen::Vector3f q = p + travel * sun_direction_;
  // An interior wall between the point and the window shades it.
  for (const Eigen::AlignedBox2f& wall : interior_walls_) {
    if (SegmentMeetsBox(p.head<2>().cast<double>(), q.head<2>().cast<double>(), wall.cast<double>())) return 0;
  }
  const int wall = exit_axis == 1 ? (sun_direction_.y() < 0 ? 0 : 1) : (sun_direction_.x() < 0 ? 2 : 3);
  const float blur_m = std::max(kSharpestEdgeM, kPenumbraPerM * travel);
  const float inset = room_.surfaces.window_frames ? static_cast<float>(room_.surfaces.frame_width_m) : 0.0f;
  float lit = 0;
  for (const WindowSpec& w : room_.windows) {
    if (WallIndex(w.wall) != wall) continue;
    const float inside = InsideWindowM(w, AlongWall(wall, q), q.z(), inset);
    lit = std::max(lit, std::clamp(0.5f + inside / blur_m, 0.0f, 1.0f));
  }
  return lit * static_cast<float>(room_.sun.warming_k_per_kw_m2) * sun_irradiance_wm2_ * cos_incidence / 1000.0f;
}

float RoomSurfaces::FrameK(int window, const Eigen::Vector3f& p) const {
  if (!room_.surfaces.window_frames) return 0;
  const WindowSpec& w = room_.windows[static_cast<size_t>(window)];
  const int wall = WallIndex(w.wall);
  const float inside = InsideWindowM(w, AlongWall(wall, p), p.z(), 0.0f);
  return inside < static_cast<float>(room_.surfaces.frame_width_m) ? frame_minus_glass_k_[static_cast<size_t>(window)]
                                                                   : 0.0f;
}

float RoomSurfaces::TextureK(int material, const Eigen::Vector3f& p) const {
  if (!room_.surfaces.texture) return 0;
  const uint64_t key = HashCombine(seed_, HashString("room.texture"), static_cast<uint64_t>(material));
  return static_cast<float>(room_.surfaces.texture_k) *
         ValueNoise3(key, p / static_cast<float>(room_.surfaces.texture_scale_m));
}

}  // namespace hoilcd
