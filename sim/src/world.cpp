#include "hoilcd/sim/world.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "hoilcd/core/random.h"

namespace hoilcd {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

void AddQuad(TriangleMesh* mesh, const Eigen::Vector3f& a, const Eigen::Vector3f& b,
             const Eigen::Vector3f& c, const Eigen::Vector3f& d, uint32_t material) {
  const auto base = static_cast<uint32_t>(mesh->positions_m.size());
  for (const Eigen::Vector3f* p : {&a, &b, &c, &d}) mesh->positions_m.push_back(*p);
  for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) mesh->indices.push_back(base + i);
  mesh->triangle_material.push_back(material);
  mesh->triangle_material.push_back(material);
}

// Posture asset for a seated person, chosen by the scene's weights (keyed by person).
// Phases and period of a person's sway and breathing, drawn from their own stream.
void DrawIdleMotion(const nlohmann::json& crowd, Rng* rng, Person* person) {
  person->sway_phase_rad = rng->Uniform(0, 2 * M_PI);
  person->breathing_phase_rad = rng->Uniform(0, 2 * M_PI);
  person->sway_period_s = crowd.at("sway_period_s").get<double>() * rng->Uniform(0.7, 1.3);
}

std::string ChoosePosture(const nlohmann::json& weights, Rng* rng) {
  static const char* kPostures[] = {"seated_upright", "seated_leaning", "seated_arms_on_table"};
  double total = 0;
  for (const char* p : kPostures) total += weights.at(p).get<double>();
  if (total <= 0) return "seated_upright";
  double pick = rng->Uniform() * total;
  for (const char* p : kPostures) {
    pick -= weights.at(p).get<double>();
    if (pick < 0) return p;
  }
  return kPostures[2];
}

Obstacle2D FootprintOf(const std::string& name, const Asset& asset, const Eigen::Vector3d& position,
                       double yaw_rad, double margin_m = 0.0) {
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

// Separating-axis test of two rectangle footprints (touching counts as overlapping).
bool RectanglesOverlap(const Obstacle2D& a, const Obstacle2D& b) {
  const Eigen::Vector2d d = b.center_m - a.center_m;
  for (const Obstacle2D* owner : {&a, &b}) {
    for (int axis = 0; axis < 2; ++axis) {
      const double angle = owner->yaw_rad + axis * M_PI / 2;
      const Eigen::Vector2d n(std::cos(angle), std::sin(angle));
      double reach = 0;
      for (const Obstacle2D* r : {&a, &b}) {
        const Eigen::Vector2d u(std::cos(r->yaw_rad), std::sin(r->yaw_rad));
        const Eigen::Vector2d v(-u.y(), u.x());
        reach += r->half_size_m.x() * std::abs(n.dot(u)) + r->half_size_m.y() * std::abs(n.dot(v));
      }
      if (std::abs(n.dot(d)) > reach) return false;
    }
  }
  return true;
}

}  // namespace

// Where instances not in the scene right now wait: below the floor, which no camera ray crosses.
const Eigen::Matrix4f kHidden = [] {
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m(2, 3) = -100.0f;
  return m;
}();

Eigen::Matrix4f PlacementTransform(const Eigen::Vector3d& position_m, double yaw_rad, double scale) {
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.topLeftCorner<3, 3>() =
      (Eigen::AngleAxisf(static_cast<float>(yaw_rad), Eigen::Vector3f::UnitZ()).toRotationMatrix() *
       static_cast<float>(scale));
  m.topRightCorner<3, 1>() = position_m.cast<float>();
  return m;
}

World::World(const Scene& scene, const BandRadianceTable& table)
    : table_(table), assets_(scene.assets_dir), caster_(std::make_unique<RayCaster>()),
      room_size_m_(scene.room_size_m) {
  environment_radiance_ = table_.RadianceFromCelsius(static_cast<float>(scene.environment_temperature_c));
  const nlohmann::json& crowd = scene.crowd;
  crowd_ = crowd;
  seed_ = scene.seed;
  frame_rate_hz_ = scene.frame_rate_hz;
  duration_s_ = scene.frames / scene.frame_rate_hz;
  seat_warmth_c_ = scene.seat_warmth_c;
  heat_print_tau_s_ = crowd.at("heat_print_time_constant_s").get<double>();
  posture_interval_s_ = crowd.at("posture_change_interval_s").get<double>();
  breathing_amplitude_m_ = crowd.at("breathing_amplitude_m").get<double>();
  breathing_period_s_ = crowd.at("breathing_period_s").get<double>();
  sway_amplitude_rad_ = crowd.at("sway_amplitude_deg").get<double>() * kDegToRad;
  for (const char* name : {"none", "floor", "ceiling", "wall", "window", "table", "chair", "person",
                           "cup", "laptop", "monitor", "radiator"}) {
    ClassId(name);
  }
  BuildRoom(scene);
  BuildFurnitureAndPeople(scene);
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const ObjectSpec& o = scene.objects[i];
    const Asset& asset = assets_.Get(o.asset);
    const double yaw = o.yaw_deg * kDegToRad;
    Place(asset, PlacementTransform(o.position_m, yaw), InstanceRole::kObject,
          asset.class_name + " " + std::to_string(i), o.temperature_offset_c);
    if (o.position_m.z() < 0.2) {
      obstacles_.push_back(FootprintOf(asset.class_name + " " + std::to_string(i), asset,
                                       o.position_m, yaw));
    }
  }
  // People standing still (chatting by a wall): present all the time, obstacles for the robot.
  for (const nlohmann::json& spec : crowd.at("standing")) {
    Rng rng = KeyedRng(seed_, "crowd.standing", static_cast<uint64_t>(people_.size()));
    Person& person = AddStandingPerson("standing", &rng);
    const Eigen::Vector3d at(spec.at("position_m").at(0).get<double>(), spec.at("position_m").at(1).get<double>(), 0.0);
    person.world_from_seat = PlacementTransform(at, spec.at("yaw_deg").get<double>() * kDegToRad);
    DrawIdleMotion(crowd, &rng, &person);
    person.lead_s = -1;  // marks a person standing still (no route to follow)
    obstacles_.push_back(Obstacle2D::Circle("standing person " + std::to_string(person.person_id), at.head<2>(), 0.3));
  }
  SetTime(0.0);
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

int World::Place(const Asset& asset, const Eigen::Matrix4f& world_from_object, InstanceRole role,
                 std::string name, double temperature_offset_c) {
  auto [it, inserted] = prototype_of_asset_.emplace(&asset, -1);
  if (inserted) it->second = caster_->AddPrototype(asset.mesh);
  const int id = caster_->AddInstance(it->second, world_from_object);
  InstanceInfo info;
  info.role = role;
  info.name = std::move(name);
  info.class_id = ClassId(asset.class_name.empty() ? "object" : asset.class_name);
  info.asset = &asset;
  info.mesh = &asset.mesh;
  for (const ThermalMaterial& tm : asset.materials) {
    InstanceMaterial m;
    m.temperature_c = m.temperature_top_c = static_cast<float>(tm.temperature_c + temperature_offset_c);
    m.emissivity = static_cast<float>(tm.emissivity);
    m.specular = tm.specular;
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
  const float inset = 0.002f;  // windows sit just inside the wall plane
  for (size_t i = 0; i < scene.windows.size(); ++i) {
    const WindowSpec& w = scene.windows[i];
    const auto a = static_cast<float>(w.center_m - 0.5 * w.width_m);
    const auto b = static_cast<float>(w.center_m + 0.5 * w.width_m);
    const auto z0 = static_cast<float>(w.bottom_m), z1 = static_cast<float>(w.bottom_m + w.height_m);
    const auto material = static_cast<uint32_t>(3 + i);
    if (w.wall == "south") AddQuad(&room_mesh_, V(a, inset, z0), V(a, inset, z1), V(b, inset, z1), V(b, inset, z0), material);
    if (w.wall == "north") AddQuad(&room_mesh_, V(a, Y - inset, z0), V(b, Y - inset, z0), V(b, Y - inset, z1), V(a, Y - inset, z1), material);
    if (w.wall == "west") AddQuad(&room_mesh_, V(inset, a, z0), V(inset, b, z0), V(inset, b, z1), V(inset, a, z1), material);
    if (w.wall == "east") AddQuad(&room_mesh_, V(X - inset, a, z0), V(X - inset, a, z1), V(X - inset, b, z1), V(X - inset, b, z0), material);
  }
  const int prototype = caster_->AddPrototype(room_mesh_);
  caster_->AddInstance(prototype, Eigen::Matrix4f::Identity());
  InstanceInfo info;
  info.role = InstanceRole::kRoom;
  info.name = "room";
  info.class_id = ClassId("wall");
  info.mesh = &room_mesh_;
  auto surface = [&](const SurfaceSpec& s, double top_c, const char* cls) {
    InstanceMaterial m;
    m.class_id = ClassId(cls);
    m.temperature_c = static_cast<float>(s.temperature_c);
    m.temperature_top_c = static_cast<float>(top_c);
    m.emissivity = static_cast<float>(s.emissivity);
    m.specular = s.specular;
    Finish(&m);
    return m;
  };
  info.materials.push_back(surface(scene.floor, scene.floor.temperature_c, "floor"));
  info.materials.push_back(surface(scene.ceiling, scene.ceiling.temperature_c, "ceiling"));
  info.materials.push_back(surface(scene.walls, scene.wall_temperature_top_c, "wall"));
  for (const WindowSpec& w : scene.windows) {
    info.materials.push_back(surface(w.surface, w.surface.temperature_c, "window"));
  }
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
}

void World::BuildFurnitureAndPeople(const Scene& scene) {
  const Asset& table_asset = assets_.Get(scene.table_asset);
  const Asset& chair_asset = assets_.Get(scene.chair_asset);
  bool three_per_side = scene.people_per_table > 4;
  for (const SeatingSpec& s : scene.seating) three_per_side |= (s.seat % 3 == 2);
  const int per_side = three_per_side ? 3 : 2;
  const double spacing = three_per_side ? scene.seat_spacing_6_m : scene.seat_spacing_4_m;
  const double half_depth = table_asset.bounds_m.max().y();
  // Half the chair's larger horizontal extent: a bound on how far a turn moves its corners.
  const Eigen::Vector3f chair_size = chair_asset.bounds_m.sizes();
  const double chair_half_width = 0.5 * std::max(chair_size.x(), chair_size.y());

  // Who sits where: the explicit list, or people_per_table random seats per table.
  std::vector<SeatingSpec> seating = scene.seating;
  if (seating.empty()) {
    for (int t = 0; t < static_cast<int>(scene.tables.size()); ++t) {
      std::vector<int> seats;
      for (int side = 0; side < 2; ++side)
        for (int k = 0; k < per_side; ++k) seats.push_back(side * 3 + k);
      Rng rng = KeyedRng(scene.seed, "crowd.seats", t);
      for (int i = static_cast<int>(seats.size()) - 1; i > 0; --i) {
        std::swap(seats[i], seats[rng.UniformInt(static_cast<uint32_t>(i + 1))]);
      }
      seats.resize(std::min<size_t>(seats.size(), scene.people_per_table));
      std::sort(seats.begin(), seats.end());
      for (int s : seats) seating.push_back({t, s, "random"});
    }
  }

  // Chairs stand where people left them, not on a grid: without this, full tables in the
  // point-symmetric paper room look the same from opposite ends of the loop. A chair moves along
  // the table, is pushed in (never pulled out: the robot drives close behind), and turns; the turn
  // is paid for by pushing it in further, so its footprint reaches no further from the table
  // than a straight chair's. Chairs whose moved footprints would overlap another chair's get
  // their moves halved until none does (the straight layout is kept as it is).
  struct ChairPlan {
    int table, seat, side, k;
    double turn, shift, push;  // full jitter: rad, m along the table, m pushed in
    double scale = 1;          // fraction of the jitter applied
  };
  std::vector<ChairPlan> chairs;
  for (int t = 0; t < static_cast<int>(scene.tables.size()); ++t) {
    for (int side = 0; side < 2; ++side) {
      for (int k = 0; k < per_side; ++k) {
        const int seat = side * 3 + k;
        Rng jitter = KeyedRng(scene.seed, "furniture.chair", t, seat);
        ChairPlan plan{t, seat, side, k, 0, 0, 0};
        plan.turn = jitter.Uniform(-1.0, 1.0) * scene.chair_jitter_deg * kDegToRad;
        plan.shift = jitter.Uniform(-1.0, 1.0) * scene.chair_jitter_m;
        plan.push = 0.5 * jitter.Uniform() * scene.chair_jitter_m;
        chairs.push_back(plan);
      }
    }
  }
  const auto chair_pose = [&](const ChairPlan& c, Eigen::Vector3d* position, double* seat_yaw) {
    const TableSpec& spec = scene.tables[c.table];
    const double yaw = spec.yaw_deg * kDegToRad;
    const double turn = c.scale * c.turn;
    const double along = (c.k - 0.5 * (per_side - 1)) * spacing + c.scale * c.shift;
    const double pushed_in = c.scale * c.push + chair_half_width * std::abs(std::sin(turn));
    const double across = (c.side == 0 ? -1.0 : 1.0) * (half_depth + scene.seat_setback_m - pushed_in);
    const Eigen::Vector2d p = spec.center_m + Eigen::Rotation2Dd(yaw) * Eigen::Vector2d(along, across);
    *position = Eigen::Vector3d(p.x(), p.y(), 0.0);
    *seat_yaw = yaw + (c.side == 0 ? M_PI / 2 : -M_PI / 2) + turn;
  };
  const auto footprint = [&](const ChairPlan& c) {
    Eigen::Vector3d position;
    double seat_yaw;
    chair_pose(c, &position, &seat_yaw);
    return FootprintOf("", chair_asset, position, seat_yaw);
  };
  constexpr int kHalvings = 6;
  for (int round = 0; round <= kHalvings; ++round) {
    std::vector<Obstacle2D> footprints;
    for (const ChairPlan& c : chairs) footprints.push_back(footprint(c));
    std::vector<bool> overlapping(chairs.size(), false);
    bool any = false;
    for (size_t i = 0; i < chairs.size(); ++i) {
      for (size_t j = i + 1; j < chairs.size(); ++j) {
        if (chairs[i].scale == 0 && chairs[j].scale == 0) continue;
        if (RectanglesOverlap(footprints[i], footprints[j])) {
          overlapping[i] = overlapping[j] = any = true;
        }
      }
    }
    if (!any) break;
    for (size_t i = 0; i < chairs.size(); ++i) {
      if (overlapping[i]) chairs[i].scale = round == kHalvings - 1 ? 0.0 : 0.5 * chairs[i].scale;
    }
  }

  size_t next_chair = 0;
  for (int t = 0; t < static_cast<int>(scene.tables.size()); ++t) {
    const TableSpec& spec = scene.tables[t];
    const double yaw = spec.yaw_deg * kDegToRad;
    const Eigen::Vector3d center(spec.center_m.x(), spec.center_m.y(), 0.0);
    Place(table_asset, PlacementTransform(center, yaw), InstanceRole::kTable, "table " + std::to_string(t), 0.0);
    obstacles_.push_back(FootprintOf("table " + std::to_string(t), table_asset, center, yaw));
    for (int n = 0; n < 2 * per_side; ++n) {
      const ChairPlan& plan = chairs[next_chair++];
      const int seat = plan.seat;
      Eigen::Vector3d seat_pos;
      double seat_yaw;
      chair_pose(plan, &seat_pos, &seat_yaw);
      const std::string chair_name = "chair " + std::to_string(t) + "." + std::to_string(seat);
      const int chair = Place(chair_asset, PlacementTransform(seat_pos, seat_yaw), InstanceRole::kChair,
                              chair_name, 0.0);
      obstacles_.push_back(FootprintOf(chair_name, chair_asset, seat_pos, seat_yaw));
      Seat record;
      record.table = t;
      record.seat = seat;
      record.chair_instance = chair;
      record.world_from_seat = PlacementTransform(seat_pos, seat_yaw);
      record.chair_materials = instances_[chair].materials;
      seats_.push_back(record);
      const auto who = std::find_if(seating.begin(), seating.end(), [&](const SeatingSpec& s) {
        return s.table == t && s.seat == seat;
      });
      if (who != seating.end()) AddSeatedPerson(t, seat, who->posture, 0.0, 1e30);
    }
  }
}

void World::SetPersonTemperatures(int instance, const Asset& body, double skin_c, double clothing_c,
                                  double hair_c) {
  InstanceInfo& info = instances_[instance];
  // Region temperatures follow the person; the asset's own values set the offsets between
  // regions (lower clothing is a little cooler than upper, shoes cooler still).
  const int upper = body.MaterialIndex("clothing_upper");
  const double asset_clothing = upper >= 0 ? body.materials[upper].temperature_c : 28.5;
  for (size_t m = 0; m < body.materials.size(); ++m) {
    const std::string& region = body.materials[m].region;
    InstanceMaterial& im = info.materials[m];
    if (region == "skin") im.temperature_c = static_cast<float>(skin_c);
    if (region == "hair") im.temperature_c = static_cast<float>(hair_c);
    if (region.rfind("clothing", 0) == 0) {
      im.temperature_c = static_cast<float>(clothing_c + body.materials[m].temperature_c - asset_clothing);
    }
    im.temperature_top_c = im.temperature_c;
    Finish(&im);
  }
}

size_t World::AddSeatedPerson(int table, int seat, const std::string& posture, double arrive_s,
                              double leave_s, int person_id) {
  const auto seat_it = std::find_if(seats_.begin(), seats_.end(),
                                    [&](const Seat& s) { return s.table == table && s.seat == seat; });
  HOILCD_CHECK(seat_it != seats_.end());
  const int id = person_id >= 0 ? person_id : NextPersonId();
  Person person;
  person.person_id = id;
  person.table = table;
  person.seat = seat;
  person.arrive_s = arrive_s;
  person.leave_s = leave_s;
  person.world_from_seat = seat_it->world_from_seat;
  Rng rng = KeyedRng(seed_, "crowd.person", id);
  const nlohmann::json& weights = crowd_.at("posture_weights");
  std::string current = posture == "random" ? ChoosePosture(weights, &rng) : posture;
  person.postures.emplace_back(arrive_s, current);
  // People shift posture now and then (exponential intervals): the upper body changes, the
  // contact with chair and table stays, which is what makes HOI points landmarks.
  if (posture_interval_s_ > 0) {
    Rng changes = KeyedRng(seed_, "crowd.posture_change", id);
    for (double t = arrive_s;;) {
      t += -posture_interval_s_ * std::log(1.0 - changes.Uniform());
      if (t >= std::min(leave_s, duration_s_)) break;
      std::string next = current;
      for (int attempt = 0; attempt < 8 && next == current; ++attempt) next = ChoosePosture(weights, &changes);
      if (next == current) continue;
      person.postures.emplace_back(t, next);
      current = next;
    }
  }
  person.height_scale = std::clamp(1.0 + crowd_.at("height_scale_sd").get<double>() * rng.Normal(), 0.8, 1.2);
  DrawIdleMotion(crowd_, &rng, &person);
  // Per-person variation, limited to ±2σ so nobody is implausibly cold or hot.
  auto varied = [&](const char* mean, const char* sd) {
    return crowd_.at(mean).get<double>() + crowd_.at(sd).get<double>() * std::clamp(rng.Normal(), -2.0, 2.0);
  };
  const double skin_c = varied("skin_temperature_c", "skin_temperature_sd_c");
  const double clothing_c = varied("clothing_temperature_c", "clothing_temperature_sd_c");
  // Skin exposure varies: some people have little hair, and their scalp reads as skin.
  const bool bald = rng.Uniform() < crowd_.at("bald_fraction").get<double>();
  const double hair_c = bald ? skin_c - 1.0
                             : crowd_.at("hair_temperature_c").get<double>() + 0.5 * std::clamp(rng.Normal(), -2.0, 2.0);
  for (const auto& [from, name] : person.postures) {
    if (person.instances.count(name)) continue;
    const Asset& body = assets_.Get("person_" + name);
    const int instance = Place(body, kHidden, InstanceRole::kPerson, "person " + std::to_string(id), 0.0);
    instances_[instance].person_id = id;
    SetPersonTemperatures(instance, body, skin_c, clothing_c, hair_c);
    person.instances[name] = instance;
  }
  people_.push_back(person);
  return people_.size() - 1;
}

void World::PlanCrowd(const std::vector<RobotSample>& samples) {
  route_.clear();
  for (const RobotSample& s : samples) route_.push_back({s.time_s, s.base.x_m, s.base.y_m, s.base.theta_rad});
  const double p = crowd_.at("turnover_probability").get<double>();
  auto frame_of = [&](double t) { return static_cast<int>(std::lround(t * frame_rate_hz_)); };
  auto seat_name = [](int table, int seat) { return std::to_string(table) + "." + std::to_string(seat); };
  // Seat turnover at every lap boundary the robot crosses.
  for (int lap = 1; p > 0 && !samples.empty() && lap <= static_cast<int>(samples.back().lap); ++lap) {
    const auto crossing = std::find_if(samples.begin(), samples.end(), [&](const RobotSample& s) { return s.lap >= lap; });
    const double t = crossing->time_s;
    const int frame = crossing->frame;
    (void)frame_of;
    std::vector<size_t> sitting;
    for (size_t i = 0; i < people_.size(); ++i) {
      if (people_[i].seated && people_[i].arrive_s <= t && people_[i].leave_s > t) sitting.push_back(i);
    }
    auto occupied = [&](const Seat& seat) {
      return std::any_of(people_.begin(), people_.end(), [&](const Person& q) {
        return q.seated && q.table == seat.table && q.seat == seat.seat && q.arrive_s <= t && q.leave_s > t;
      });
    };
    for (size_t i : sitting) {
      Rng rng = KeyedRng(seed_, "crowd.turnover", lap, people_[i].person_id);
      const double u = rng.Uniform();
      if (u < p) {  // leaves the room
        people_[i].leave_s = t;
        events_.push_back({frame, "leave", people_[i].person_id, seat_name(people_[i].table, people_[i].seat), ""});
      } else if (u < 1.5 * p) {  // moves to a free seat, if there is one
        std::vector<const Seat*> free;
        for (const Seat& seat : seats_)
          if (!occupied(seat)) free.push_back(&seat);
        if (free.empty()) continue;
        const Seat& to = *free[rng.UniformInt(static_cast<uint32_t>(free.size()))];
        Person moved = people_[i];
        people_[i].leave_s = t;
        const std::string from = seat_name(moved.table, moved.seat);
        // The same person (same id, so the same appearance), on another seat.
        AddSeatedPerson(to.table, to.seat, "random", t, moved.leave_s, moved.person_id);
        events_.push_back({frame, "swap", moved.person_id, seat_name(to.table, to.seat), "from seat " + from});
      }
    }
    for (const Seat& seat : seats_) {
      if (occupied(seat)) continue;
      Rng rng = KeyedRng(seed_, "crowd.arrival", lap, seat.table * 16 + seat.seat);
      if (rng.Uniform() >= p) continue;
      const size_t index = AddSeatedPerson(seat.table, seat.seat, "random", t, 1e30);
      events_.push_back({frame, "arrive", people_[index].person_id, seat_name(seat.table, seat.seat), ""});
    }
  }
  // Walkers walk the robot's route a few seconds ahead of it: between the camera and the
  // seated people (the occlusion knob), never in the robot's way.
  const int walkers = crowd_.at("walkers").get<int>();
  for (int w = 0; w < walkers; ++w) {
    Rng rng = KeyedRng(seed_, "crowd.walker", w);
    Person& walker = AddStandingPerson("walker", &rng);
    walker.lead_s = rng.Uniform(4.0, 9.0);  // 1.7-3.9 m ahead at cruise speed
    walker.lead_amplitude_s = rng.Uniform(0.5, 1.5);
    walker.lead_period_s = rng.Uniform(15.0, 30.0);
    walker.lead_phase_rad = rng.Uniform(0, 2 * M_PI);
    walker.lateral_m = rng.Uniform(0.0, 0.04);  // to the left: the tables are on the right of a clockwise lap
  }
  std::sort(events_.begin(), events_.end(), [](const DatasetEvent& a, const DatasetEvent& b) {
    return a.frame != b.frame ? a.frame < b.frame : a.person < b.person;
  });
}

int World::NextPersonId() const {
  int id = 0;
  for (const Person& p : people_) id = std::max(id, p.person_id + 1);
  return id;
}

Person& World::AddStandingPerson(const std::string& kind, Rng* rng) {
  const int id = NextPersonId();
  const Asset& body = assets_.Get("person_standing");
  Person person;
  person.person_id = id;
  person.seated = false;
  person.postures.emplace_back(0.0, "standing");
  person.height_scale = std::clamp(1.0 + crowd_.at("height_scale_sd").get<double>() * rng->Normal(), 0.85, 1.15);
  const int instance = Place(body, kHidden, InstanceRole::kPerson, kind + " " + std::to_string(id), 0.0);
  instances_[instance].person_id = id;
  SetPersonTemperatures(instance, body,
                        crowd_.at("skin_temperature_c").get<double>() + 0.5 * std::clamp(rng->Normal(), -2.0, 2.0),
                        crowd_.at("clothing_temperature_c").get<double>() + 0.5 * std::clamp(rng->Normal(), -2.0, 2.0),
                        crowd_.at("hair_temperature_c").get<double>());
  person.instances["standing"] = instance;
  people_.push_back(person);
  return people_.back();
}

void World::UpdateSeatWarmth(double time_s) {
  for (const Seat& seat : seats_) {
    // Body heat while someone sits; afterwards the seat cools exponentially (a heat print).
    double warmth = 0;
    for (const Person& p : people_) {
      if (!p.seated || p.table != seat.table || p.seat != seat.seat || p.arrive_s > time_s) continue;
      warmth = std::max(warmth, p.leave_s > time_s
                                    ? seat_warmth_c_
                                    : seat_warmth_c_ * std::exp(-(time_s - p.leave_s) / heat_print_tau_s_));
    }
    std::vector<InstanceMaterial>& materials = instances_[seat.chair_instance].materials;
    for (size_t m = 0; m < materials.size(); ++m) {
      if (seat.chair_materials[m].specular) continue;  // metal legs do not hold body heat
      materials[m].temperature_c = seat.chair_materials[m].temperature_c + static_cast<float>(warmth);
      materials[m].temperature_top_c = materials[m].temperature_c;
      Finish(&materials[m]);
    }
  }
}

void World::SetTime(double time_s) {
  for (Person& p : people_) {
    p.present = time_s >= p.arrive_s && time_s < p.leave_s;
    // A walker whose place on the route lies beyond the end of the sequence has walked off
    // (otherwise it would wait at the robot's final pose for the robot to drive into it).
    if (!p.seated && p.lead_s >= 0 && !route_.empty() &&
        time_s + p.lead_s + p.lead_amplitude_s > route_.back()[0]) {
      p.present = false;
    }
    p.posture.clear();
    for (const auto& [from, name] : p.postures)
      if (from <= time_s) p.posture = name;
    p.instance = p.present ? p.instances.at(p.posture) : -1;
    Eigen::Matrix4f world_from_body = kHidden;
    if (p.present && (p.seated || p.lead_s < 0)) {  // seated, or standing still
      const double sway = sway_amplitude_rad_ * std::sin(2 * M_PI * time_s / p.sway_period_s + p.sway_phase_rad);
      const double breath = breathing_amplitude_m_ *
                            std::sin(2 * M_PI * time_s / breathing_period_s_ + p.breathing_phase_rad);
      // Breathing lifts the upper body a few millimetres: a vertical stretch about the floor.
      Eigen::Matrix4f local = Eigen::Matrix4f::Identity();
      local.topLeftCorner<3, 3>() =
          Eigen::AngleAxisf(static_cast<float>(sway), Eigen::Vector3f::UnitZ()).toRotationMatrix() *
          static_cast<float>(p.height_scale);
      local(2, 2) *= static_cast<float>(1.0 + breath / 1.3);
      world_from_body = p.world_from_seat * local;
    } else if (p.present && !route_.empty()) {
      // Where the robot will be lead seconds from now, with a small bob of the gait.
      const double lead = p.lead_s + p.lead_amplitude_s * std::sin(2 * M_PI * time_s / p.lead_period_s + p.lead_phase_rad);
      const double t = std::clamp(time_s + lead, route_.front()[0], route_.back()[0]);
      const auto after = std::lower_bound(route_.begin(), route_.end(), t,
                                          [](const std::array<double, 4>& r, double v) { return r[0] < v; });
      const std::array<double, 4>& b = after == route_.end() ? route_.back() : *after;
      const std::array<double, 4>& a = after == route_.begin() || after == route_.end() ? b : *(after - 1);
      const double f = b[0] > a[0] ? (t - a[0]) / (b[0] - a[0]) : 0.0;
      const double heading = a[3] + f * std::remainder(b[3] - a[3], 2 * M_PI);
      const Eigen::Vector3d position(a[1] + f * (b[1] - a[1]) - p.lateral_m * std::sin(heading),
                                     a[2] + f * (b[2] - a[2]) + p.lateral_m * std::cos(heading),
                                     0.02 * std::abs(std::sin(2 * M_PI * 0.9 * time_s + p.lead_phase_rad)));
      world_from_body = PlacementTransform(position, heading, p.height_scale);
    }
    for (const auto& [name, instance] : p.instances) {
      caster_->SetInstanceTransform(instance, instance == p.instance ? world_from_body : kHidden);
    }
  }
  UpdateSeatWarmth(time_s);
  caster_->Commit();
}

}  // namespace hoilcd
