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

// A seated posture by the scene's weights; people with a laptop in front of them keep their
// forearms off the table (they type on the laptop instead).
std::string ChoosePosture(const nlohmann::json& weights, bool has_laptop, Rng* rng) {
  static const char* kPostures[] = {"seated_upright", "seated_leaning_back", "seated_leaning", "seated_arms_on_table"};
  auto weight = [&](const char* p) {
    const bool on_table = std::string(p) == "seated_leaning" || std::string(p) == "seated_arms_on_table";
    return has_laptop && on_table ? 0.0 : weights.at(p).get<double>();
  };
  double total = 0;
  for (const char* p : kPostures) total += weight(p);
  if (total <= 0) return "seated_upright";
  double pick = rng->Uniform() * total;
  for (const char* p : kPostures) {
    pick -= weight(p);
    if (pick < 0 && weight(p) > 0) return p;
  }
  return "seated_upright";
}

Eigen::Matrix4d Scaled(const Eigen::Matrix4f& world_from_frame, double scale) {
  Eigen::Matrix4d m = world_from_frame.cast<double>();
  m.topLeftCorner<3, 3>() *= scale;
  return m;
}

Eigen::Vector3d Apply(const Eigen::Matrix4d& m, const Eigen::Vector3d& p) {
  return m.topLeftCorner<3, 3>() * p + m.topRightCorner<3, 1>();
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
  skeleton_ = std::make_unique<Skeleton>(assets_);
  activity_options_ = ActivityOptions::FromCrowd(scene.crowd);
  if (const std::string problem = activity_options_.Check(); !problem.empty()) throw InputError(scene.file, problem);
  environment_radiance_ = table_.RadianceFromCelsius(static_cast<float>(scene.environment_temperature_c));
  const nlohmann::json& crowd = scene.crowd;
  crowd_ = crowd;
  scene_file_ = scene.file;
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
  info.label = id;
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

  table_bounds_m_ = table_asset.bounds_m;  // every table is the same asset
  size_t next_chair = 0;
  for (int t = 0; t < static_cast<int>(scene.tables.size()); ++t) {
    const TableSpec& spec = scene.tables[t];
    const double yaw = spec.yaw_deg * kDegToRad;
    const Eigen::Vector3d center(spec.center_m.x(), spec.center_m.y(), 0.0);
    Place(table_asset, PlacementTransform(center, yaw), InstanceRole::kTable, "table " + std::to_string(t), 0.0);
    world_from_table_.push_back(PlacementTransform(center, yaw).cast<double>());
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
  person.table_from_seat = world_from_table_.at(table).inverse() * person.world_from_seat.cast<double>();
  Rng rng = KeyedRng(seed_, "crowd.person", id);
  // What is on the table in front of them (the same for the person wherever they sit).
  Rng props = KeyedRng(seed_, "crowd.props", id);
  const bool has_cup = props.Uniform() < activity_options_.cup_fraction;
  const bool has_laptop = props.Uniform() < activity_options_.laptop_fraction;
  const nlohmann::json& weights = crowd_.at("posture_weights");
  std::string current = posture == "random" ? ChoosePosture(weights, has_laptop, &rng) : posture;
  person.postures.emplace_back(arrive_s, current);
  // People shift posture now and then (exponential intervals): the upper body changes, the
  // contact with chair and table stays, which is what makes HOI points landmarks.
  if (posture_interval_s_ > 0) {
    Rng changes = KeyedRng(seed_, "crowd.posture_change", id);
    for (double t = arrive_s;;) {
      t += -posture_interval_s_ * std::log(1.0 - changes.Uniform());
      if (t >= std::min(leave_s, duration_s_)) break;
      std::string next = current;
      for (int attempt = 0; attempt < 8 && next == current; ++attempt) next = ChoosePosture(weights, has_laptop, &changes);
      if (next == current) continue;
      person.postures.emplace_back(t, next);
      current = next;
    }
  }
  // The other seats seen from this one: neighbours at the same table, as directions (for
  // talking and glances); elbow room, half the distance to the nearest seat beside this one
  // (any table).
  std::vector<double> neighbours;
  const Eigen::Matrix4d seat_from_world = person.world_from_seat.cast<double>().inverse();
  for (const Seat& other : seats_) {
    if (other.table == table && other.seat == seat) continue;
    const Eigen::Vector3d at = Apply(seat_from_world, other.world_from_seat.cast<double>().topRightCorner<3, 1>());
    if (other.table == table) neighbours.push_back(std::atan2(at.y(), at.x()));
    if (std::abs(at.x()) < 0.35) person.elbow_room_m = std::min(person.elbow_room_m, 0.5 * std::abs(at.y()));
  }
  // How far the table's near edge is (the poses and props assume 0.30 m; chairs stand irregularly).
  {
    const Eigen::Vector3d q = person.table_from_seat.topRightCorner<3, 1>();
    const Eigen::Vector3d d = person.table_from_seat.topLeftCorner<3, 3>().col(0);
    const double half_depth = 0.5 * (table_bounds_m_.max().y() - table_bounds_m_.min().y());
    if (std::abs(d.y()) > 0.5) person.table_edge_m = std::clamp((std::abs(q.y()) - half_depth) / std::abs(d.y()), 0.1, 0.5);
  }
  person.activities = PlanActivities(activity_options_, seed_, id, arrive_s, std::min(leave_s, duration_s_ + 1.0),
                                     has_cup, has_laptop, neighbours);
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
  person.parts = AddBody(id, "person " + std::to_string(id), skin_c, clothing_c, hair_c);
  person.instance = person.parts[0];
  // Props: a cup to the right of the hands, a laptop (its user side towards the person) in the
  // middle; positions in the seat frame, relative to the body's size.
  const std::string where = " " + std::to_string(table) + "." + std::to_string(seat);
  if (has_cup) {
    person.cup_at_m = Eigen::Vector3d(person.table_edge_m + 0.17, -0.21, 0.74);
    person.cup = Place(assets_.Get("cup"), kHidden, InstanceRole::kObject, "cup" + where, 0.0);
  }
  if (has_laptop) {
    person.laptop_at_m = Eigen::Vector3d(person.table_edge_m + 0.22, 0.0, 0.74);
    person.laptop = Place(assets_.Get("laptop"), kHidden, InstanceRole::kObject, "laptop" + where, 0.0);
  }
  people_.push_back(person);
  return people_.size() - 1;
}

std::array<int, Skeleton::kPartCount> World::AddBody(int person_id, const std::string& name, double skin_c,
                                                      double clothing_c, double hair_c) {
  std::array<int, Skeleton::kPartCount> parts{};
  for (int i = 0; i < Skeleton::kPartCount; ++i) {
    const Asset& part = skeleton_->part(i);
    parts[i] = Place(part, kHidden, InstanceRole::kPerson, name, 0.0);
    instances_[parts[i]].person_id = person_id;
    instances_[parts[i]].label = parts[0];
    SetPersonTemperatures(parts[i], part, skin_c, clothing_c, hair_c);
  }
  return parts;
}

void World::PlanCrowd(const std::vector<RobotSample>& samples) {
  robot_ = RobotTrack(samples);
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
  // Walkers: bouts on the robot's route ahead of it (between the camera and the seated people:
  // the occlusion knob), across its path and past it, clear of furniture, the robot and each other.
  const int walkers = crowd_.at("walkers").get<int>();
  std::map<std::string, double> behaviour_weights;
  for (const auto& [name, weight] : crowd_.at("walker_behaviours").items()) behaviour_weights[name] = weight.get<double>();
  walker_plans_.clear();
  for (int w = 0; w < walkers; ++w) {
    Rng rng = KeyedRng(seed_, "crowd.walker", w);
    Person& walker = AddStandingPerson("walker", &rng);
    walker.walker = w;
    walker.lead_s = rng.Uniform(4.0, 9.0);
    walker.lead_amplitude_s = rng.Uniform(0.5, 1.5);
    walker.lead_period_s = rng.Uniform(15.0, 30.0);
    walker.lead_phase_rad = rng.Uniform(0, 2 * M_PI);
    walker.lateral_m = rng.Uniform(0.0, 0.04);  // to the left: the tables are on the right of a clockwise lap
    const auto space = std::make_shared<const FreeSpace>(obstacles_, kWalkerRadiusM * walker.height_scale);
    for (const RobotSample& s : samples) {
      const Eigen::Vector2d at(s.base.x_m, s.base.y_m);
      if (space->FreeAlong(at, Eigen::Vector2d(-std::sin(s.base.theta_rad), std::cos(s.base.theta_rad)), kWalkerMaxSidestepM)) continue;
      std::string nearest;
      const double clearance = space->Clearance(at, &nearest);
      throw InputError(scene_file_, "/route/waypoints_m: walkers (crowd.walkers) follow the robot's route, which passes " +
                                        std::to_string(clearance + space->radius_m()).substr(0, 5) + " m from " + nearest +
                                        " at t = " + std::to_string(s.time_s).substr(0, 6) + " s with no room to step aside; a walker's body needs " +
                                        std::to_string(space->radius_m()).substr(0, 5) +
                                        " m: move the route away from it or set crowd.walkers to 0");
    }
    walker_plans_.push_back(PlanWalker(behaviour_weights, seed_, w, duration_s_, space, robot_, walker_plans_));
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
  Person person;
  person.person_id = id;
  person.seated = false;
  person.postures.emplace_back(0.0, "standing");
  person.height_scale = std::clamp(1.0 + crowd_.at("height_scale_sd").get<double>() * rng->Normal(), 0.85, 1.15);
  person.parts = AddBody(id, kind + " " + std::to_string(id),
                         crowd_.at("skin_temperature_c").get<double>() + 0.5 * std::clamp(rng->Normal(), -2.0, 2.0),
                         crowd_.at("clothing_temperature_c").get<double>() + 0.5 * std::clamp(rng->Normal(), -2.0, 2.0),
                         crowd_.at("hair_temperature_c").get<double>());
  person.instance = person.parts[0];
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

BodyPose World::PoseOf(const Person& p, double time_s, Eigen::Matrix4d* world_from_person) const {
  const double sway = sway_amplitude_rad_ * std::sin(2 * M_PI * time_s / p.sway_period_s + p.sway_phase_rad);
  const double breath = breathing_amplitude_m_ * std::sin(2 * M_PI * time_s / breathing_period_s_ + p.breathing_phase_rad);
  if (p.seated || p.lead_s < 0) {  // seated, or standing still
    // Seated bodies scale within the pose (hips stay on the seat, feet on the floor, hands
    // reach the same table); standing bodies scale about the floor.
    *world_from_person = Scaled(p.world_from_seat, p.seated ? 1.0 : p.height_scale);
    // The base posture, blending from the previous one after a change.
    size_t k = 0;
    for (size_t i = 0; i < p.postures.size(); ++i)
      if (p.postures[i].first <= time_s) k = i;
    BodyPose pose = PresetPose(p.postures[k].second);
    if (k > 0) {
      const double w = SmoothStep((time_s - p.postures[k].first) / activity_options_.posture_blend_s);
      pose = Blend(PresetPose(p.postures[k - 1].second), pose, w);
    }
    if (p.seated) {
      // Hands resting on the table keep their distance from its near edge.
      for (ArmPose& arm : pose.arm) {
        if (arm.wrist_m.z() > 0.74) arm.wrist_m.x() += p.table_edge_m - 0.30;
      }
      pose.scale = p.height_scale;
      skeleton_->SitOnSeat(&pose);
    }
    // Idle sway of the upper body and head; breathing lifts the chest (a small spine extension).
    pose.dof[kLumbarTwist] += 0.5 * sway;
    pose.dof[kNeckTwist] += sway;
    pose.dof[kLumbarFlex] -= breath / 0.5;
    return pose;
  }
  // A walker: where its plan puts it, the gait phase from the distance walked (so the feet do
  // not slide), its stride from its speed.
  const WalkerPlan& plan = walker_plans_.at(p.walker);
  const WalkerPlacement place = PlaceWalker(plan, robot_, time_s, p.lateral_m);
  *world_from_person =
      PlacementTransform(Eigen::Vector3d(place.at_m.x(), place.at_m.y(), 0.0), place.heading_rad, p.height_scale).cast<double>();
  if (place.speed_m_s < 0.03) return PresetPose("standing");
  const double stride_m = Skeleton::StrideAt(place.speed_m_s) * p.height_scale;
  const double phase = 2 * M_PI * plan.Walked(time_s) * robot_.cruise_speed_m_s() / stride_m + p.lead_phase_rad;
  return skeleton_->Walking(phase, stride_m / p.height_scale);
}

void World::KeepClearOfTable(const Person& p, BodyPose* pose) const {
  // The table top slab in the table frame, grown by a few millimetres of clearance.
  constexpr double kClearanceM = 0.004;
  const Eigen::Vector3f lo = table_bounds_m_.min(), hi = table_bounds_m_.max();
  const double top = hi.z() + kClearanceM, bottom = hi.z() - 0.03 - kClearanceM;
  // How deep the part's mesh reaches into the slab from above (0 if it does not).
  auto depth = [&](const Eigen::Matrix4d& seat_from_part, int part) {
    const Eigen::Matrix4d m = p.table_from_seat * seat_from_part;
    double deepest = 0;
    for (const Eigen::Vector3f& v : skeleton_->part(part).mesh.positions_m) {
      const Eigen::Vector3d q = Apply(m, v.cast<double>());
      if (q.x() > lo.x() - kClearanceM && q.x() < hi.x() + kClearanceM && q.y() > lo.y() - kClearanceM &&
          q.y() < hi.y() + kClearanceM && q.z() < top && q.z() > bottom) {
        deepest = std::max(deepest, top - q.z());
      }
    }
    return deepest;
  };
  for (int iteration = 0; iteration < 8; ++iteration) {
    const auto parts = skeleton_->PartTransforms(*pose);
    bool moved = false;
    // Trunk and head against the table edge: lean less.
    if (depth(parts[1], 1) > 0 || depth(parts[2], 2) > 0 || depth(parts[3], 3) > 0) {
      pose->dof[kLumbarFlex] -= 3 * M_PI / 180;
      moved = true;
    }
    // Arms on the table top: lift the wrist (and the elbow) by the depth.
    for (int s = 0; s < 2; ++s) {
      double lift = 0;
      for (int k = 0; k < 3; ++k) lift = std::max(lift, depth(parts[4 + 6 * s + k], 4 + 6 * s + k));
      if (lift > 0) {
        pose->arm[s].wrist_m.z() += lift + 0.002;
        pose->arm[s].elbow_hint.z() += 0.5;
        moved = true;
      }
    }
    if (!moved) return;
  }
}

void World::SetTime(double time_s) {
  for (Person& p : people_) {
    p.present = time_s >= p.arrive_s && time_s < p.leave_s;
    // A walker whose place on the route lies beyond the end of the sequence has walked off
    // (otherwise it would wait at the robot's final pose for the robot to drive into it).
    if (p.walker >= 0) p.present = PlaceWalker(walker_plans_.at(p.walker), robot_, time_s).present;
    p.posture.clear();
    for (const auto& [from, name] : p.postures)
      if (from <= time_s) p.posture = name;
    p.activity.clear();
    p.contacts_m.clear();
    if (!p.present) {
      for (int part : p.parts) caster_->SetInstanceTransform(part, kHidden);
      for (int prop : {p.cup, p.laptop})
        if (prop >= 0) caster_->SetInstanceTransform(prop, kHidden);
      continue;
    }
    Eigen::Matrix4d world_from_person;
    BodyPose pose = PoseOf(p, time_s, &world_from_person);
    if (p.walker >= 0) p.posture = walker_plans_[p.walker].At(time_s).behaviour;
    Eigen::Matrix4d seat_from_cup = Eigen::Matrix4d::Identity();
    seat_from_cup.topRightCorner<3, 1>() = p.cup_at_m;
    const auto episode = std::find_if(p.activities.begin(), p.activities.end(), [&](const ActivityEpisode& e) {
      return e.start_s <= time_s && time_s < e.end_s;
    });
    if (episode != p.activities.end()) {
      p.activity = episode->name;
      const Eigen::Vector2d robot = robot_.At(time_s);
      const Eigen::Vector3d robot_in_seat =
          Apply(world_from_person.inverse(), Eigen::Vector3d(robot.x(), robot.y(), 0.0));
      pose = ApplyActivity(*skeleton_, pose, *episode, time_s, activity_options_.blend_s,
                           {p.cup_at_m, p.laptop_at_m}, std::atan2(robot_in_seat.y(), robot_in_seat.x()), &seat_from_cup);
    }
    if (p.seated) {
      // Close neighbours: elbows tucked in and hands kept within the person's own half.
      if (p.elbow_room_m < 0.30) {
        for (int s = 0; s < 2; ++s) {
          const double sign = s == 0 ? 1 : -1;
          pose.arm[s].elbow_hint.y() = -sign * std::clamp((0.30 - p.elbow_room_m) * 5, 0.0, 0.6);  // towards the body
          pose.arm[s].wrist_m.y() = sign * std::min(sign * pose.arm[s].wrist_m.y(), p.elbow_room_m - 0.1);
        }
      }
      KeepClearOfTable(p, &pose);
    }
    pose = skeleton_->Limit(pose);
    const auto parts = skeleton_->PartTransforms(pose);
    for (int i = 0; i < Skeleton::kPartCount; ++i) {
      caster_->SetInstanceTransform(p.parts[i], (world_from_person * parts[i]).cast<float>());
    }
    const auto keypoints = skeleton_->Keypoints(parts);
    for (int k = 0; k < kCocoKeypointCount; ++k) p.keypoints_m[k] = Apply(world_from_person, keypoints[k]);
    // Contacts with the chair, the table and the floor follow the moving parts.
    if (p.seated) {
      p.contacts_m.emplace_back("seat", Apply(world_from_person, Eigen::Vector3d(pose.pelvis_m.x() + 0.02, pose.pelvis_m.y(), 0.45)));
      for (int s = 0; s < 2; ++s) {
        const Eigen::Vector3d elbow = keypoints[7 + s], wrist = keypoints[9 + s];
        if (wrist.z() > 0.80 || wrist.x() < 0.33) continue;  // forearm not on the table top
        const Eigen::Vector3d mid = 0.5 * (elbow + wrist);
        p.contacts_m.emplace_back("table", Apply(world_from_person, Eigen::Vector3d(std::max(0.33, mid.x()), mid.y(), 0.74)));
      }
    }
    for (const auto& [name, at] : skeleton_->FootContacts(parts)) {
      if (at.z() < 0.02) p.contacts_m.emplace_back(name, Apply(world_from_person, at));
    }
    // Props: the cup rests or travels with the hand; the laptop faces its user.
    const Eigen::Matrix4d world_from_seat = p.world_from_seat.cast<double>();
    if (p.cup >= 0) caster_->SetInstanceTransform(p.cup, (world_from_seat * seat_from_cup).cast<float>());
    if (p.laptop >= 0) {
      Eigen::Matrix4d seat_from_laptop = Eigen::Matrix4d::Identity();
      seat_from_laptop.topLeftCorner<3, 3>() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      seat_from_laptop.topRightCorner<3, 1>() = p.laptop_at_m;
      caster_->SetInstanceTransform(p.laptop, (world_from_seat * seat_from_laptop).cast<float>());
    }
  }
  UpdateSeatWarmth(time_s);
  caster_->Commit();
}

}  // namespace hoilcd
