#include "hoilcd/sim/world/world.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Geometry>

#include "hoilcd/core/util/random.h"
#include "hoilcd/core/util/text.h"

namespace hoilcd {
namespace {

constexpr double kDegToRad = M_PI / 180.0;
constexpr float kDriveOverM = 0.02f;  // m: a floor object no higher than this (a rug) is driven over

void AddQuad(TriangleMesh* mesh, const Eigen::Vector3f& a, const Eigen::Vector3f& b, const Eigen::Vector3f& c,
             const Eigen::Vector3f& d, uint32_t material) {
  const auto base = static_cast<uint32_t>(mesh->positions_m.size());
  for (const Eigen::Vector3f* p : {&a, &b, &c, &d}) mesh->positions_m.push_back(*p);
  for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) mesh->indices.push_back(base + i);
  mesh->triangle_material.push_back(material);
  mesh->triangle_material.push_back(material);
}

Obstacle2D FootprintOf(const std::string& name, const Asset& asset, const Eigen::Vector3d& position, double yaw_rad,
                       double margin_m = 0.0) {
  const Eigen::Vector3f lo = asset.bounds_m.min(), hi = asset.bounds_m.max();
  const Eigen::Vector2d center_local(0.5 * (lo.x() + hi.x()), 0.5 * (lo.y() + hi.y()));
  const Eigen::Rotation2Dd rot(yaw_rad);
  Obstacle2D o;
  o.name = name;
  o.shape = Obstacle2D::Shape::kRectangle;
  o.center_m = position.head<2>() + rot * center_local;
  o.half_size_m = Eigen::Vector2d(0.5 * (hi.x() - lo.x()) + margin_m, 0.5 * (hi.y() - lo.y()) + margin_m);
  o.yaw_rad = yaw_rad;
  return o;
}

// Chairs stand where people left them, not on a grid: without this, full tables in the
// point-symmetric paper room look the same from opposite ends of the loop. A chair moves along
// the table, is pushed in (never pulled out: the robot drives close behind), and turns; the turn
// is paid for by pushing it in further, so its footprint reaches no further from the table
// than a straight chair's. Chairs whose moved footprints would overlap another chair's get
// their moves halved until none does (the straight layout is kept as it is). Tables seat people
// on both long sides, on one (-y) side, or around them (facing the centre); sofas have no chairs.
class ChairLayout {
 public:
  struct Chair {
    int table, seat, side, k;
    double turn, shift, push;  // full jitter: rad, m along the table, m pushed in
    double scale = 1;          // fraction of the jitter applied
    double shift_scale = 1;    // and of the shift along the table
  };

  // Chairs of every table in order (table, then side, then place along the side), jittered.
  ChairLayout(const Scene& scene, const std::vector<const Asset*>& table_assets, const Asset& chair_asset, int per_side,
              double spacing_m)
      : scene_(scene),
        table_assets_(table_assets),
        chair_asset_(chair_asset),
        per_side_(per_side),
        spacing_m_(spacing_m) {
    // Half the chair's larger horizontal extent: a bound on how far a turn moves its corners.
    const Eigen::Vector3f chair_size = chair_asset.bounds_m.sizes();
    chair_half_width_m_ = 0.5 * std::max(chair_size.x(), chair_size.y());
    for (int t = 0; t < static_cast<int>(scene.tables.size()); ++t) {
      const TableSpec& spec = scene.tables[t];
      if (spec.seats == SeatArrangement::kSofa) continue;
      for (int seat : SeatsOf(spec, per_side)) {
        Rng jitter = KeyedRng(scene.seed, "furniture.chair", t, seat);
        Chair chair{t, seat, seat / 3, seat % 3, 0, 0, 0};
        if (spec.seats != SeatArrangement::kBothSides) chair = Chair{t, seat, 0, seat, 0, 0, 0};
        chair.turn = jitter.Uniform(-1.0, 1.0) * scene.furniture.chair_jitter_deg * kDegToRad;
        chair.shift = jitter.Uniform(-1.0, 1.0) * scene.furniture.chair_jitter_m;
        chair.push = 0.5 * jitter.Uniform() * scene.furniture.chair_jitter_m;
        chairs_.push_back(chair);
      }
    }
    Settle();
  }

  const std::vector<Chair>& chairs() const { return chairs_; }

  // Where a chair stands (floor point below the seat) and which way its seat faces.
  void Pose(const Chair& c, Eigen::Vector3d* position, double* seat_yaw) const {
    const TableSpec& spec = scene_.tables[c.table];
    const Eigen::AlignedBox3f& bounds = table_assets_[c.table]->bounds_m;
    const double yaw = spec.yaw_deg * kDegToRad;
    const double turn = c.scale * c.turn;
    const double shift = c.scale * c.shift_scale * c.shift;
    const double pushed_in = c.scale * c.push + chair_half_width_m_ * std::abs(std::sin(turn));
    const double setback_m = scene_.furniture.seat_setback_m;
    Eigen::Vector2d local;
    double facing = 0;  // the seat's yaw in the table frame
    if (spec.seats == SeatArrangement::kAround) {
      // Evenly round the table, the first seat on -y, each set back from the ellipse the
      // footprint's half sizes span (a round top's circle; a square's sides, for four seats).
      const double angle = -M_PI / 2 + 2 * M_PI * c.k / spec.seat_count;
      const Eigen::Vector2d out(std::cos(angle), std::sin(angle));
      const double hx = 0.5 * bounds.sizes().x(), hy = 0.5 * bounds.sizes().y();
      const double reach = 1.0 / std::hypot(out.x() / hx, out.y() / hy);
      local = out * (reach + setback_m - pushed_in) + Eigen::Vector2d(-out.y(), out.x()) * shift;
      facing = angle + M_PI;
    } else {
      const int count = spec.seats == SeatArrangement::kBothSides ? per_side_ : spec.seat_count;
      const double spacing = spec.seats == SeatArrangement::kBothSides ? spacing_m_ : bounds.sizes().x() / count;
      const double half_depth = spec.seats == SeatArrangement::kBothSides ? bounds.max().y() : -bounds.min().y();
      const double along = (c.k - 0.5 * (count - 1)) * spacing + shift;
      local = Eigen::Vector2d(along, (c.side == 0 ? -1.0 : 1.0) * (half_depth + setback_m - pushed_in));
      facing = c.side == 0 ? M_PI / 2 : -M_PI / 2;
    }
    const Eigen::Vector2d p = spec.center_m + Eigen::Rotation2Dd(yaw) * local;
    *position = Eigen::Vector3d(p.x(), p.y(), 0.0);
    *seat_yaw = yaw + facing + turn;
  }

 private:
  Obstacle2D Footprint(const Chair& c) const {
    Eigen::Vector3d position;
    double seat_yaw;
    Pose(c, &position, &seat_yaw);
    return FootprintOf("", chair_asset_, position, seat_yaw);
  }

  Eigen::Vector2d SeatAt(Chair c, double scale) const {
    c.scale *= scale;
    Eigen::Vector3d position;
    double seat_yaw;
    Pose(c, &position, &seat_yaw);
    return Eigen::Vector2d(position.head<2>());
  }

  // Halves the moves of chairs that overlap another; seats side by side (closer than kCloseSeatsM
  // when straight) are not shifted more than 1 cm closer together (their shifts are halved until
  // so): seated neighbours' shoulder joints are 0.38 m apart at body scale 1, so a crowded row
  // (0.45 m) has nothing to give.
  void Settle() {
    constexpr double kCloseSeatsM = 0.6, kSqueezeM = 0.01;
    constexpr int kHalvings = 6;
    // Seats closer than kCloseSeatsM when straight: discs of half that radius that meet.
    std::vector<Obstacle2D> straight_seats;
    for (const Chair& c : chairs_) straight_seats.push_back(Obstacle2D::Circle("", SeatAt(c, 0), 0.5 * kCloseSeatsM));
    const std::vector<std::pair<size_t, size_t>> close_seats = OverlappingFootprints(straight_seats);
    for (int round = 0; round <= kHalvings; ++round) {
      std::vector<Obstacle2D> footprints;
      for (const Chair& c : chairs_) footprints.push_back(Footprint(c));
      std::vector<bool> overlapping(chairs_.size(), false), squeezed(chairs_.size(), false);
      bool any = false;
      for (const auto& [i, j] : close_seats) {
        if (chairs_[i].scale == 0 && chairs_[j].scale == 0) continue;
        const double straight_m = (SeatAt(chairs_[i], 0) - SeatAt(chairs_[j], 0)).norm();
        if (straight_m < kCloseSeatsM &&
            (SeatAt(chairs_[i], 1) - SeatAt(chairs_[j], 1)).norm() < straight_m - kSqueezeM) {
          squeezed[i] = squeezed[j] = any = true;
        }
      }
      for (const auto& [i, j] : OverlappingFootprints(footprints)) {
        if (chairs_[i].scale == 0 && chairs_[j].scale == 0) continue;
        overlapping[i] = overlapping[j] = any = true;
      }
      if (!any) break;
      for (size_t i = 0; i < chairs_.size(); ++i) {
        if (overlapping[i]) chairs_[i].scale = round == kHalvings - 1 ? 0.0 : 0.5 * chairs_[i].scale;
        if (squeezed[i]) chairs_[i].shift_scale = round == kHalvings - 1 ? 0.0 : 0.5 * chairs_[i].shift_scale;
      }
    }
  }

  const Scene& scene_;
  const std::vector<const Asset*>& table_assets_;
  const Asset& chair_asset_;
  const int per_side_;
  const double spacing_m_;
  double chair_half_width_m_ = 0;
  std::vector<Chair> chairs_;
};

// Tables may touch (pushed together into one long table) but not stand in one another: footprints
// overlapping by more than kTouchM are refused, naming both tables' JSON paths.
void CheckTablesApart(const Scene& scene, const std::vector<const Asset*>& table_assets) {
  constexpr double kTouchM = 0.01;
  std::vector<Obstacle2D> footprints;
  for (size_t t = 0; t < scene.tables.size(); ++t) {
    const TableSpec& spec = scene.tables[t];
    const Eigen::Vector3d center(spec.center_m.x(), spec.center_m.y(), 0.0);
    footprints.push_back(
        FootprintOf("table " + std::to_string(t), *table_assets[t], center, spec.yaw_deg * kDegToRad, -kTouchM));
  }
  ProblemCollector problems;
  for (const auto& [i, j] : OverlappingFootprints(footprints)) {
    const Eigen::Vector2d& a = scene.tables[i].center_m;
    problems.Add(scene.file + ": /tables/" + std::to_string(j),
                 "stands in /tables/" + std::to_string(i) + " (centred at (" + ShortestDouble(a.x()) + ", " +
                     ShortestDouble(a.y()) + ")): their footprints overlap; expected tables apart or touching");
  }
  problems.ThrowIfAny();
}

}  // namespace

Eigen::Matrix4f PlacementTransform(const Eigen::Vector3d& position_m, double yaw_rad, double scale) {
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.topLeftCorner<3, 3>() =
      (Eigen::AngleAxisf(static_cast<float>(yaw_rad), Eigen::Vector3f::UnitZ()).toRotationMatrix() *
       static_cast<float>(scale));
  m.topRightCorner<3, 1>() = position_m.cast<float>();
  return m;
}

World::World(const Scene& scene, const BandRadianceTable& table, int threads)
    : table_(table),
      assets_(scene.assets_dir),
      caster_(std::make_unique<RayCaster>()),
      room_size_m_(scene.room.size_m) {
  crowd_ = std::make_unique<Crowd>(scene, &assets_, static_cast<CrowdStage*>(this));
  environment_radiance_ = table_.RadianceFromCelsius(static_cast<float>(scene.room.environment_temperature_c));
  for (const char* name : {"none", "floor", "ceiling", "wall", "window", "table", "chair", "person", "cup", "laptop",
                           "monitor", "radiator"}) {
    ClassId(name);
  }
  BuildRoom(scene);
  BuildFurnitureAndPeople(scene);
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const ObjectSpec& o = scene.objects[i];
    const Asset& asset = assets_.Get(o.asset);
    const double yaw = o.yaw_deg * kDegToRad;
    const int id = Place(asset, PlacementTransform(o.position_m, yaw), InstanceRole::kObject,
                         asset.class_name + " " + std::to_string(i), o.temperature_offset_c);
    instances_[static_cast<size_t>(id)].fixture = true;
    // A floor object the robot drives over (a rug, at most kDriveOverM high) is no obstacle.
    if (asset.mount == "floor" && o.position_m.z() < 0.2 && asset.bounds_m.max().z() > kDriveOverM) {
      obstacles_.push_back(FootprintOf(asset.class_name + " " + std::to_string(i), asset, o.position_m, yaw));
    }
  }
  // People standing still (chatting by a wall): present all the time, obstacles for the robot.
  for (Obstacle2D& o : crowd_->AddStandingPeople(scene)) obstacles_.push_back(std::move(o));
  std::vector<Eigen::AlignedBox2f> interior_walls;
  for (const WallPart& part : WallParts(scene.floor, room_size_m_.z())) {
    if (!part.lintel)
      interior_walls.emplace_back(part.box_m.min().head<2>().cast<float>(), part.box_m.max().head<2>().cast<float>());
  }
  room_surfaces_ = std::make_unique<RoomSurfaces>(
      scene.room, scene.seed, RadiatorBoxes(instances_, ClassId("radiator")), interior_walls, scene.clock_offset_s);
  if (scene.room.thermal.enabled) {
    room_network_ = std::make_unique<RoomNetwork>(scene.room, scene.room.thermal, scene.seed, room_surfaces_->climate(),
                                                  RoomQuads(scene), instances_, room_instance_,
                                                  room_surfaces_->exterior_walls(), table_, threads);
  }
  // The materials' first state; the thermal solution waits for the first SetTime, after
  // PlanCrowd has told it who sits where (its spin-up is solved once).
  MoveTo(0.0, /*solve=*/false);
}

void World::PlanCrowd(const std::vector<RobotSample>& samples) {
  crowd_->Plan(samples, obstacles_);
  if (room_network_ == nullptr) return;
  // Seated and standing people as spheres of a body's radiating area: 1.8 m² (DuBois) times the
  // effective radiation area factor, 0.70 seated and 0.73 standing (ISO 7726 / Fanger), about the
  // chest, at a clothed surface's 28 °C (ISO 7730 at 22 °C air: clothing surfaces 27–30 °C).
  // Walkers are left out: one passes a patch within seconds, and a few W/m² for ten seconds warm
  // a plaster skin of about 2.7 kJ/(m²·K) by about 0.02 K, well under the sensor's NETD.
  constexpr double kBodyAreaM2 = 1.8;
  constexpr double kSeatedAreaFactor = 0.70, kStandingAreaFactor = 0.73;
  constexpr double kSeatedChestM = 0.8, kStandingChestM = 1.3;
  std::vector<PersonSource> sources;
  for (const Person& person : crowd_->people()) {
    const bool standing_still = !person.seated && person.lead_s < 0;
    if (!person.seated && !standing_still) continue;
    const double chest_m = person.seated ? kSeatedChestM : kStandingChestM;
    const double area_m2 = kBodyAreaM2 * (person.seated ? kSeatedAreaFactor : kStandingAreaFactor);
    PersonSource source;
    const Eigen::Vector4f chest =
        person.world_from_seat * Eigen::Vector4f(0, 0, static_cast<float>(chest_m * person.height_scale), 1);
    source.centre_m = chest.head<3>();
    source.radius_m = std::sqrt(area_m2 / (4 * M_PI)) * person.height_scale;
    source.arrive_s = person.arrive_s;
    source.leave_s = person.leave_s;
    sources.push_back(source);
  }
  room_network_->SetPeople(sources);
}

namespace {

// A window sits 2 mm in front of its wall, whose rectangle runs on behind the glass: cuts each
// wall quad on the lines of the windows in front of it and drops the cells behind a window, so
// that no patch of the thermal solution is hidden from the room.
std::vector<RoomQuad> SplitAroundWindows(const std::vector<RoomQuad>& quads, size_t windows) {
  constexpr float kInFrontM = 0.01f;
  std::vector<RoomQuad> out;
  for (const RoomQuad& quad : quads) {
    const Eigen::Vector3f origin = quad.corners[0], u = quad.corners[1] - origin, v = quad.corners[3] - origin;
    auto uv = [&](const Eigen::Vector3f& p) {
      return Eigen::Vector2f((p - origin).dot(u) / u.squaredNorm(), (p - origin).dot(v) / v.squaredNorm());
    };
    std::vector<Eigen::AlignedBox2f> holes;  // windows in front of this quad, in its (u, v)
    for (const RoomQuad& other : quads) {
      const bool window = other.material >= 3 && other.material < 3 + static_cast<int>(windows);
      if (!window || quad.material != 2 || other.normal.dot(quad.normal) < 0.99f) continue;
      if (std::abs((other.corners[0] - origin).dot(quad.normal)) > kInFrontM) continue;
      Eigen::AlignedBox2f box;
      for (const Eigen::Vector3f& c : other.corners) box.extend(uv(c));
      box = box.intersection(Eigen::AlignedBox2f(Eigen::Vector2f::Zero(), Eigen::Vector2f::Ones()));
      if (!box.isEmpty() && box.volume() > 0) holes.push_back(box);
    }
    if (holes.empty()) {
      out.push_back(quad);
      continue;
    }
    std::vector<float> us = {0, 1}, vs = {0, 1};
    for (const Eigen::AlignedBox2f& h : holes) {
      us.insert(us.end(), {h.min().x(), h.max().x()});
      vs.insert(vs.end(), {h.min().y(), h.max().y()});
    }
    for (std::vector<float>* cuts : {&us, &vs}) {
      std::sort(cuts->begin(), cuts->end());
      cuts->erase(std::unique(cuts->begin(), cuts->end(), [](float a, float b) { return b - a < 1e-4f; }), cuts->end());
    }
    for (size_t j = 0; j + 1 < vs.size(); ++j) {
      for (size_t i = 0; i + 1 < us.size(); ++i) {
        const Eigen::Vector2f mid(0.5f * (us[i] + us[i + 1]), 0.5f * (vs[j] + vs[j + 1]));
        if (std::any_of(holes.begin(), holes.end(), [&](const Eigen::AlignedBox2f& h) { return h.contains(mid); }))
          continue;
        RoomQuad cell = quad;
        cell.corners = {origin + us[i] * u + vs[j] * v, origin + us[i + 1] * u + vs[j] * v,
                        origin + us[i + 1] * u + vs[j + 1] * v, origin + us[i] * u + vs[j + 1] * v};
        out.push_back(cell);
      }
    }
  }
  return out;
}

}  // namespace

std::vector<RoomQuad> World::RoomQuads(const Scene& scene) const {
  const std::vector<WallPart> parts = WallParts(scene.floor, room_size_m_.z());
  const Eigen::Vector3f size = room_size_m_.cast<float>();
  // In the room's air: inside its shell and in no interior wall.
  auto in_air = [&](const Eigen::Vector3f& p) {
    if ((p.array() < 0).any() || (p.array() > size.array()).any()) return false;
    for (const WallPart& part : parts) {
      if (part.box_m.contains(p.cast<double>())) return false;
    }
    return true;
  };
  std::vector<RoomQuad> quads;
  for (size_t q = 0; 2 * q < room_mesh_.TriangleCount(); ++q) {
    RoomQuad quad;
    for (size_t k = 0; k < 4; ++k) quad.corners[k] = room_mesh_.positions_m[4 * q + k];
    quad.material = static_cast<int>(room_mesh_.triangle_material[2 * q]);
    quad.normal = (quad.corners[1] - quad.corners[0]).cross(quad.corners[3] - quad.corners[0]).normalized();
    const Eigen::Vector3f centre = 0.25f * (quad.corners[0] + quad.corners[1] + quad.corners[2] + quad.corners[3]);
    if (!in_air(centre + 0.01f * quad.normal)) quad.normal = -quad.normal;
    quads.push_back(quad);
  }
  return SplitAroundWindows(quads, scene.room.windows.size());
}

void World::ApplyRoomNetwork() {
  const RoomNetwork& network = *room_network_;
  for (size_t w = 0; w < instances_.size(); ++w) {
    InstanceInfo& info = instances_[w];
    for (size_t k = 0; k < info.materials.size(); ++k) {
      InstanceMaterial& m = info.materials[k];
      const float incident = network.IncidentRadiance(static_cast<int>(w), static_cast<int>(k));
      if (!std::isnan(incident)) m.environment_radiance = incident;
      if (w == static_cast<size_t>(room_instance_)) continue;
      const float solved_c = network.InstanceTemperatureC(static_cast<int>(w), static_cast<int>(k));
      if (std::isnan(solved_c)) continue;
      m.temperature_c = m.temperature_top_c = solved_c;
      Finish(&m);
    }
  }
  environment_radiance_ = network.MeanIncidentRadiance();
}

void World::SetTime(double time_s) { MoveTo(time_s, /*solve=*/true); }

void World::MoveTo(double time_s, bool solve) {
  crowd_->SetTime(time_s);
  solve = solve && room_network_ != nullptr;
  if (solve) {
    room_network_->SetTime(time_s);
    room_surfaces_->AttachNetwork(room_network_.get());
  }
  std::vector<InstanceMaterial>& room = instances_[static_cast<size_t>(room_instance_)].materials;
  room_surfaces_->SetTime(time_s, &room);
  for (InstanceMaterial& m : room) Finish(&m);
  environment_radiance_ =
      table_.RadianceFromCelsius(static_cast<float>(room_surfaces_->EnvironmentTemperatureC(time_s)));
  if (solve) ApplyRoomNetwork();
  caster_->Commit();
}

void World::Move(int instance, const Eigen::Matrix4f& world_from_object) {
  caster_->SetInstanceTransform(instance, world_from_object);
  instances_[instance].object_from_world = world_from_object.inverse();
}

int World::ClassId(const std::string& name) {
  const auto it = classes_.find(name);
  if (it != classes_.end()) return it->second;
  const int id = static_cast<int>(classes_.size());
  classes_[name] = id;
  return id;
}

void World::Finish(InstanceMaterial* m) const {
  m->blackbody_bottom = table_.RadianceFromCelsius(m->temperature_c);
  m->blackbody_top = table_.RadianceFromCelsius(m->temperature_top_c);
}

int World::Place(const Asset& asset, const Eigen::Matrix4f& world_from_object, InstanceRole role, std::string name,
                 double temperature_offset_c) {
  auto [it, inserted] = prototype_of_asset_.emplace(&asset, -1);
  if (inserted) it->second = caster_->AddPrototype(asset.mesh);
  const int id = caster_->AddInstance(it->second, world_from_object);
  InstanceInfo info;
  info.role = role;
  info.name = std::move(name);
  info.class_id = ClassId(asset.class_name.empty() ? "object" : asset.class_name);
  info.asset = &asset;
  info.mesh = &asset.mesh;
  info.label = id;
  info.object_from_world = world_from_object.inverse();
  for (const ThermalMaterial& tm : asset.materials) {
    InstanceMaterial m;
    m.temperature_c = m.temperature_top_c = static_cast<float>(tm.temperature_c + temperature_offset_c);
    m.emissivity = static_cast<float>(tm.emissivity);
    m.specular = tm.specular;
    m.roughness_um = static_cast<float>(tm.roughness_um);
    m.class_id = info.class_id;
    Finish(&m);
    info.materials.push_back(m);
  }
  instances_.push_back(std::move(info));
  return id;
}

void World::BuildRoom(const Scene& scene) {
  const auto X = static_cast<float>(room_size_m_.x()), Y = static_cast<float>(room_size_m_.y()),
             Z = static_cast<float>(room_size_m_.z());
  using V = Eigen::Vector3f;
  AddQuad(&room_mesh_, V(0, 0, 0), V(X, 0, 0), V(X, Y, 0), V(0, Y, 0), 0);  // floor
  AddQuad(&room_mesh_, V(0, 0, Z), V(0, Y, Z), V(X, Y, Z), V(X, 0, Z), 1);  // ceiling
  AddQuad(&room_mesh_, V(0, 0, 0), V(0, 0, Z), V(X, 0, Z), V(X, 0, 0), 2);  // south
  AddQuad(&room_mesh_, V(0, Y, 0), V(X, Y, 0), V(X, Y, Z), V(0, Y, Z), 2);  // north
  AddQuad(&room_mesh_, V(0, 0, 0), V(0, Y, 0), V(0, Y, Z), V(0, 0, Z), 2);  // west
  AddQuad(&room_mesh_, V(X, 0, 0), V(X, 0, Z), V(X, Y, Z), V(X, Y, 0), 2);  // east
  const float inset = 0.002f;                                               // windows sit just inside the wall plane
  for (size_t i = 0; i < scene.room.windows.size(); ++i) {
    const WindowSpec& w = scene.room.windows[i];
    const auto a = static_cast<float>(w.center_m - 0.5 * w.width_m);
    const auto b = static_cast<float>(w.center_m + 0.5 * w.width_m);
    const auto z0 = static_cast<float>(w.bottom_m), z1 = static_cast<float>(w.bottom_m + w.height_m);
    const auto material = static_cast<uint32_t>(3 + i);
    if (w.wall == "south")
      AddQuad(&room_mesh_, V(a, inset, z0), V(a, inset, z1), V(b, inset, z1), V(b, inset, z0), material);
    if (w.wall == "north")
      AddQuad(&room_mesh_, V(a, Y - inset, z0), V(b, Y - inset, z0), V(b, Y - inset, z1), V(a, Y - inset, z1),
              material);
    if (w.wall == "west")
      AddQuad(&room_mesh_, V(inset, a, z0), V(inset, b, z0), V(inset, b, z1), V(inset, a, z1), material);
    if (w.wall == "east")
      AddQuad(&room_mesh_, V(X - inset, a, z0), V(X - inset, a, z1), V(X - inset, b, z1), V(X - inset, b, z0),
              material);
  }
  // Interior walls (a building floor): boxes in the walls' material, after the windows'.
  const std::vector<WallPart> wall_parts = WallParts(scene.floor, room_size_m_.z());
  const auto interior_material = static_cast<uint32_t>(3 + scene.room.windows.size());
  for (const WallPart& part : wall_parts) {
    const Eigen::Vector3f lo = part.box_m.min().cast<float>(), hi = part.box_m.max().cast<float>();
    AddQuad(&room_mesh_, V(lo.x(), lo.y(), lo.z()), V(lo.x(), lo.y(), hi.z()), V(hi.x(), lo.y(), hi.z()),
            V(hi.x(), lo.y(), lo.z()), interior_material);  // -y
    AddQuad(&room_mesh_, V(lo.x(), hi.y(), lo.z()), V(hi.x(), hi.y(), lo.z()), V(hi.x(), hi.y(), hi.z()),
            V(lo.x(), hi.y(), hi.z()), interior_material);  // +y
    AddQuad(&room_mesh_, V(lo.x(), lo.y(), lo.z()), V(lo.x(), hi.y(), lo.z()), V(lo.x(), hi.y(), hi.z()),
            V(lo.x(), lo.y(), hi.z()), interior_material);  // -x
    AddQuad(&room_mesh_, V(hi.x(), lo.y(), lo.z()), V(hi.x(), lo.y(), hi.z()), V(hi.x(), hi.y(), hi.z()),
            V(hi.x(), hi.y(), lo.z()), interior_material);  // +x
    if (part.lintel)
      AddQuad(&room_mesh_, V(lo.x(), lo.y(), lo.z()), V(hi.x(), lo.y(), lo.z()), V(hi.x(), hi.y(), lo.z()),
              V(lo.x(), hi.y(), lo.z()), interior_material);  // soffit
  }
  const int prototype = caster_->AddPrototype(room_mesh_);
  caster_->AddInstance(prototype, Eigen::Matrix4f::Identity());
  InstanceInfo info;
  info.role = InstanceRole::kRoom;
  info.name = "room";
  info.class_id = ClassId("wall");
  info.mesh = &room_mesh_;
  // bottom_c at the floor, top_c at the ceiling (equal but for the walls).
  auto surface = [&](double bottom_c, double top_c, double emissivity, bool specular, const char* cls,
                     double roughness_um = 0) {
    InstanceMaterial m;
    m.roughness_um = static_cast<float>(roughness_um);
    m.class_id = ClassId(cls);
    m.temperature_c = static_cast<float>(bottom_c);
    m.temperature_top_c = static_cast<float>(top_c);
    m.emissivity = static_cast<float>(emissivity);
    m.specular = specular;
    Finish(&m);
    return m;
  };
  auto plain = [&](const SurfaceSpec& s, const char* cls) {
    return surface(s.temperature_c, s.temperature_c, s.emissivity, s.specular, cls, s.roughness_um);
  };
  const WallOptions& walls = scene.room.walls;
  info.materials.push_back(plain(scene.room.floor, "floor"));
  info.materials.push_back(plain(scene.room.ceiling, "ceiling"));
  info.materials.push_back(
      surface(walls.temperature_bottom_c, walls.temperature_top_c, walls.emissivity, walls.specular, "wall"));
  for (const WindowSpec& w : scene.room.windows) info.materials.push_back(plain(w.surface, "window"));
  if (!wall_parts.empty()) {
    info.materials.push_back(
        surface(walls.temperature_bottom_c, walls.temperature_top_c, walls.emissivity, walls.specular, "wall"));
  }
  room_instance_ = static_cast<int>(instances_.size());
  instances_.push_back(std::move(info));
  const double t = 0.05;  // walls as thin obstacles just outside the room
  auto wall = [&](const std::string& name, double cx, double cy, double hx, double hy) {
    Obstacle2D o;
    o.name = name;
    o.shape = Obstacle2D::Shape::kRectangle;
    o.center_m = {cx, cy};
    o.half_size_m = {hx, hy};
    obstacles_.push_back(o);
  };
  wall("south wall", 0.5 * X, -t, 0.5 * X + t, t);
  wall("north wall", 0.5 * X, Y + t, 0.5 * X + t, t);
  wall("west wall", -t, 0.5 * Y, t, 0.5 * Y + t);
  wall("east wall", X + t, 0.5 * Y, t, 0.5 * Y + t);
  for (size_t i = 0; i < wall_parts.size(); ++i) {
    const WallPart& part = wall_parts[i];
    if (part.lintel) continue;
    const Eigen::Vector2d lo = part.box_m.min().head<2>(), hi = part.box_m.max().head<2>();
    wall("interior wall " + std::to_string(part.wall) + "." + std::to_string(i), 0.5 * (lo.x() + hi.x()),
         0.5 * (lo.y() + hi.y()), 0.5 * (hi.x() - lo.x()), 0.5 * (hi.y() - lo.y()));
  }
}

void World::BuildFurnitureAndPeople(const Scene& scene) {
  std::vector<const Asset*> table_assets;
  for (const TableSpec& spec : scene.tables) {
    table_assets.push_back(&assets_.Get(spec.asset.empty() ? scene.furniture.table_asset : spec.asset));
  }
  CheckTablesApart(scene, table_assets);
  const Asset& chair_asset = assets_.Get(scene.furniture.chair_asset);
  bool three_per_side = scene.crowd.people_per_table > 4;
  for (const SeatingSpec& s : scene.crowd.seating) {
    if (scene.tables[s.table].seats == SeatArrangement::kBothSides) three_per_side |= (s.seat % 3 == 2);
  }
  const int per_side = three_per_side ? 3 : 2;
  const double spacing = three_per_side ? scene.furniture.seat_spacing_6_m : scene.furniture.seat_spacing_4_m;
  // Seated bodies are capped in size to fit between neighbours (Crowd::Plan), down to the
  // smallest body drawn; closer seats leave no room for anyone (1 cm more for chair jitter).
  const double narrowest_m =
      2 * kMinSeatedBodyScale * crowd_->skeleton().UpperBodyHalfExtentM().y() + kSeatedShoulderGapM + 0.01;
  if (per_side > 1 && spacing < narrowest_m) {
    std::ostringstream message;
    message << (three_per_side ? "/furniture/seat_spacing_6_m" : "/furniture/seat_spacing_4_m") << ": seats " << spacing
            << " m apart leave no room for a seated person (the narrowest body is "
            << Fixed(narrowest_m - 0.01 - kSeatedShoulderGapM, 3) << " m across the shoulders); expected at least "
            << Fixed(narrowest_m, 3) << " m";
    throw InputError(scene.file, message.str());
  }
  const std::vector<SeatingSpec> seating = Crowd::InitialSeating(scene, per_side);
  const ChairLayout layout(scene, table_assets, chair_asset, per_side, spacing);

  size_t next_chair = 0;
  for (int t = 0; t < static_cast<int>(scene.tables.size()); ++t) {
    const TableSpec& spec = scene.tables[t];
    const Asset& table_asset = *table_assets[t];
    const double yaw = spec.yaw_deg * kDegToRad;
    const Eigen::Vector3d center(spec.center_m.x(), spec.center_m.y(), 0.0);
    const int table_instance =
        Place(table_asset, PlacementTransform(center, yaw), InstanceRole::kTable, "table " + std::to_string(t), 0.0);
    instances_[static_cast<size_t>(table_instance)].fixture = true;
    crowd_->AddTable(PlacementTransform(center, yaw).cast<double>(), table_asset.bounds_m, spec.seats, table_instance);
    obstacles_.push_back(FootprintOf("table " + std::to_string(t), table_asset, center, yaw));
    for (int seat : SeatsOf(spec, per_side)) {
      Eigen::Vector3d seat_pos;
      double seat_yaw;
      int chair = -1;
      if (spec.seats == SeatArrangement::kSofa) {
        // People sit on the piece itself: seat_count places spread over its inner 5/6, facing +x.
        const double along =
            (seat - 0.5 * (spec.seat_count - 1)) * (table_asset.bounds_m.sizes().y() * 5.0 / 6.0) / spec.seat_count;
        const Eigen::Vector2d p = spec.center_m + Eigen::Rotation2Dd(yaw) * Eigen::Vector2d(0.0, along);
        seat_pos = Eigen::Vector3d(p.x(), p.y(), 0.0);
        seat_yaw = yaw;
      } else {
        const ChairLayout::Chair& plan = layout.chairs()[next_chair++];
        layout.Pose(plan, &seat_pos, &seat_yaw);
        const std::string chair_name = "chair " + std::to_string(t) + "." + std::to_string(seat);
        chair = Place(chair_asset, PlacementTransform(seat_pos, seat_yaw), InstanceRole::kChair, chair_name, 0.0);
        instances_[static_cast<size_t>(chair)].fixture = true;
        obstacles_.push_back(FootprintOf(chair_name, chair_asset, seat_pos, seat_yaw));
      }
      crowd_->AddSeat(t, seat, chair, PlacementTransform(seat_pos, seat_yaw));
      const auto who = std::find_if(seating.begin(), seating.end(),
                                    [&](const SeatingSpec& s) { return s.table == t && s.seat == seat; });
      if (who != seating.end()) crowd_->AddSeatedPerson(t, seat, who->posture, 0.0, 1e30);
    }
  }
}

}  // namespace hoilcd
