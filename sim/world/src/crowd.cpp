#include "hoilcd/sim/world/crowd.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace hoilcd {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

// Phases and period of a person's sway and breathing, drawn from their own stream.
void DrawIdleMotion(const CrowdOptions& crowd, Rng* rng, Person* person) {
  person->sway_phase_rad = rng->Uniform(0, 2 * M_PI);
  person->breathing_phase_rad = rng->Uniform(0, 2 * M_PI);
  person->sway_period_s = crowd.sway_period_s * rng->Uniform(0.7, 1.3);
}

// A seated posture by the scene's weights; people with a laptop in front of them keep their
// forearms off the table (they type on the laptop instead).
std::string ChoosePosture(const PostureWeights& weights, bool has_laptop, Rng* rng) {
  static const char* kPostures[] = {"seated_upright", "seated_leaning_back", "seated_leaning", "seated_arms_on_table"};
  auto weight = [&](const char* p) {
    const bool on_table = std::string(p) == "seated_leaning" || std::string(p) == "seated_arms_on_table";
    return has_laptop && on_table ? 0.0 : weights.Of(p);
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

// Where instances not in the scene right now wait: below the floor, which no camera ray crosses.
const Eigen::Matrix4f kHidden = [] {
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m(2, 3) = -100.0f;
  return m;
}();

}  // namespace

Crowd::Crowd(const Scene& scene, AssetLibrary* assets, CrowdStage* stage)
    : assets_(*assets), stage_(*stage), skeleton_(std::make_unique<Skeleton>(*assets)) {
  options_ = scene.crowd;
  scene_file_ = scene.file;
  seed_ = scene.run_seed;  // each recording run its own occupants
  frame_rate_hz_ = scene.frame_rate_hz;
  duration_s_ = scene.frames / scene.frame_rate_hz;
  seat_warmth_c_ = scene.furniture.seat_warmth_c;
  room_c_ = scene.room.environment_temperature_c;
  sway_amplitude_rad_ = options_.sway_amplitude_deg * kDegToRad;
  thermal_environment_ = {scene.room.environment_temperature_c, scene.room.environment_temperature_c,
                          options_.garments.air_speed_m_s};
  // Each door faces into the room from the wall it is on (the nearest wall: the scene checked it
  // lies on one).
  const Eigen::Vector2d size = scene.room.size_m.head<2>();
  for (const DoorSpec& d : scene.room.doors) {
    const std::array<double, 4> gap = {d.position_m.x(), size.x() - d.position_m.x(), d.position_m.y(),
                                       size.y() - d.position_m.y()};
    const std::array<Eigen::Vector2d, 4> inward = {Eigen::Vector2d(1, 0), Eigen::Vector2d(-1, 0), Eigen::Vector2d(0, 1),
                                                   Eigen::Vector2d(0, -1)};
    const auto wall = std::min_element(gap.begin(), gap.end()) - gap.begin();
    doors_.push_back({d.position_m, inward[static_cast<size_t>(wall)], d.width_m});
  }
}

std::vector<SeatingSpec> Crowd::InitialSeating(const Scene& scene, int per_side) {
  std::vector<SeatingSpec> seating = scene.crowd.seating;
  if (!seating.empty()) return seating;
  for (int t = 0; t < static_cast<int>(scene.tables.size()); ++t) {
    std::vector<int> seats = SeatsOf(scene.tables[t], per_side);
    Rng rng = KeyedRng(scene.run_seed, "crowd.seats", t);
    for (int i = static_cast<int>(seats.size()) - 1; i > 0; --i) {
      std::swap(seats[i], seats[rng.UniformInt(static_cast<uint32_t>(i + 1))]);
    }
    seats.resize(std::min<size_t>(seats.size(), scene.crowd.people_per_table));
    std::sort(seats.begin(), seats.end());
    for (int s : seats) seating.push_back({t, s, "random"});
  }
  return seating;
}

void Crowd::AddTable(const Eigen::Matrix4d& world_from_table, const Eigen::AlignedBox3f& table_bounds_m,
                     SeatArrangement seats, int table_instance) {
  table_instance_.push_back(table_instance);
  world_from_table_.push_back(world_from_table);
  table_bounds_m_.push_back(table_bounds_m);
  table_seats_.push_back(seats);
}

std::vector<Crowd::SeatPlace> Crowd::SeatPlaces() const {
  std::vector<SeatPlace> places;
  for (const Seat& s : seats_) places.push_back({s.table, s.seat, s.world_from_seat, s.chair_instance >= 0});
  return places;
}

void Crowd::AddSeat(int table, int seat, int chair_instance, const Eigen::Matrix4f& world_from_seat) {
  Seat record;
  record.table = table;
  record.seat = seat;
  record.chair_instance = chair_instance;
  record.world_from_seat = world_from_seat;
  if (chair_instance >= 0) record.chair_materials = stage_.MutableInstance(chair_instance).materials;
  seats_.push_back(record);
}

std::vector<Obstacle2D> Crowd::AddStandingPeople(const Scene& scene) {
  std::vector<Obstacle2D> obstacles;
  for (const StandingSpec& spec : scene.crowd.standing) {
    Rng rng = KeyedRng(seed_, "crowd.standing", static_cast<uint64_t>(people_.size()));
    Person& person = AddStandingPerson("standing", &rng);
    Dress(&person);
    const Eigen::Vector3d at(spec.position_m.x(), spec.position_m.y(), 0.0);
    person.world_from_seat = PlacementTransform(at, spec.yaw_deg * kDegToRad);
    DrawIdleMotion(options_, &rng, &person);
    person.lead_s = -1;  // marks a person standing still (no route to follow)
    obstacles.push_back(Obstacle2D::Circle("standing person " + std::to_string(person.person_id), at.head<2>(), 0.3));
  }
  return obstacles;
}

void Crowd::SetPersonTemperatures(int instance, const Asset& body, double skin_c, double clothing_c, double hair_c) {
  InstanceInfo& info = stage_.MutableInstance(instance);
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
    stage_.Finish(&im);
  }
}

size_t Crowd::AddSeatedPerson(int table, int seat, const std::string& posture, double arrive_s, double leave_s,
                              int person_id) {
  const auto seat_it =
      std::find_if(seats_.begin(), seats_.end(), [&](const Seat& s) { return s.table == table && s.seat == seat; });
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
  // On a sofa there is no table top: no props, and no posture resting on one.
  person.at_table_top = table_seats_.at(table) != SeatArrangement::kSofa;
  Rng props = KeyedRng(seed_, "crowd.props", id);
  const bool has_cup = props.Uniform() < options_.activity.cup_fraction && person.at_table_top;
  const bool has_laptop = props.Uniform() < options_.activity.laptop_fraction && person.at_table_top;
  const bool hands_off_table = has_laptop || !person.at_table_top;
  const PostureWeights& weights = options_.posture_weights;
  std::string current = posture == "random" ? ChoosePosture(weights, hands_off_table, &rng) : posture;
  person.postures.emplace_back(arrive_s, current);
  // People shift posture now and then (exponential intervals): the upper body changes, the
  // contact with chair and table stays, which is what makes HOI points landmarks.
  if (options_.posture_change_interval_s > 0) {
    Rng changes = KeyedRng(seed_, "crowd.posture_change", id);
    for (double t = arrive_s;;) {
      t += -options_.posture_change_interval_s * std::log(1.0 - changes.Uniform());
      if (t >= std::min(leave_s, duration_s_)) break;
      std::string next = current;
      for (int attempt = 0; attempt < 8 && next == current; ++attempt)
        next = ChoosePosture(weights, hands_off_table, &changes);
      if (next == current) continue;
      person.postures.emplace_back(t, next);
      current = next;
    }
  }
  // How far the table's near edge is (the poses and props assume 0.30 m; chairs stand irregularly).
  {
    const Eigen::Vector3d q = person.table_from_seat.topRightCorner<3, 1>();
    const Eigen::Vector3d d = person.table_from_seat.topLeftCorner<3, 3>().col(0);
    const Eigen::AlignedBox3f& bounds = table_bounds_m_.at(table);
    const double half_depth = 0.5 * (bounds.max().y() - bounds.min().y());
    if (table_seats_.at(table) == SeatArrangement::kAround) {
      // Seats round a table face its centre: the edge is where the ellipse its footprint's half
      // sizes span meets the line from the seat to the centre.
      const double hx = 0.5 * bounds.sizes().x(), hy = half_depth, r = std::hypot(q.x(), q.y());
      person.table_edge_m = std::clamp(r - r / std::hypot(q.x() / hx, q.y() / hy), 0.1, 0.5);
    } else if (std::abs(d.y()) > 0.5) {
      person.table_edge_m = std::clamp((std::abs(q.y()) - half_depth) / std::abs(d.y()), 0.1, 0.5);
    }
  }
  // Whom they look at is settled by AimGazes, once every seat and sitter is known.
  person.activities =
      PlanActivities(options_.activity, seed_, id, arrive_s, std::min(leave_s, duration_s_ + 1.0), has_cup, has_laptop);
  person.height_scale = std::clamp(1.0 + options_.height_scale_sd * rng.Normal(), kMinSeatedBodyScale, 1.2);
  DrawIdleMotion(options_, &rng, &person);
  // Per-person variation, limited to ±2σ so nobody is implausibly cold or hot.
  auto varied = [&](double mean, double sd) { return mean + sd * std::clamp(rng.Normal(), -2.0, 2.0); };
  const double skin_c = varied(options_.skin_temperature_c, options_.skin_temperature_sd_c);
  const double clothing_c = varied(options_.clothing_temperature_c, options_.clothing_temperature_sd_c);
  // Skin exposure varies: some people have little hair, and their scalp reads as skin.
  const bool bald = rng.Uniform() < options_.bald_fraction;
  const double hair_c = bald ? skin_c - 1.0 : options_.hair_temperature_c + 0.5 * std::clamp(rng.Normal(), -2.0, 2.0);
  person.parts = AddBody(id, "person " + std::to_string(id), skin_c, clothing_c, hair_c);
  person.instance = person.parts[0];
  // Props: a cup to the right of the hands, a laptop (its user side towards the person) in the
  // middle; positions in the seat frame, relative to the body's size.
  const std::string where = " " + std::to_string(table) + "." + std::to_string(seat);
  if (has_cup) {
    person.cup_at_m = Eigen::Vector3d(person.table_edge_m + 0.17, -0.21, 0.74);
    person.cup = stage_.Place(assets_.Get("cup"), kHidden, InstanceRole::kObject, "cup" + where, 0.0);
  }
  if (has_laptop) {
    person.laptop_at_m = Eigen::Vector3d(person.table_edge_m + 0.22, 0.0, 0.74);
    person.laptop = stage_.Place(assets_.Get("laptop"), kHidden, InstanceRole::kObject, "laptop" + where, 0.0);
  }
  Dress(&person);
  people_.push_back(person);
  return people_.size() - 1;
}

std::array<int, Skeleton::kPartCount> Crowd::AddBody(int person_id, const std::string& name, double skin_c,
                                                     double clothing_c, double hair_c) {
  std::array<int, Skeleton::kPartCount> parts{};
  for (int i = 0; i < Skeleton::kPartCount; ++i) {
    const Asset& part = skeleton_->part(i);
    parts[i] = stage_.Place(part, kHidden, InstanceRole::kPerson, name, 0.0);
    stage_.MutableInstance(parts[i]).person_id = person_id;
    stage_.MutableInstance(parts[i]).label = parts[0];
    SetPersonTemperatures(parts[i], part, skin_c, clothing_c, hair_c);
  }
  return parts;
}

void Crowd::Plan(const std::vector<RobotSample>& samples, const std::vector<Obstacle2D>& obstacles) {
  robot_ = RobotTrack(samples);
  PlanTurnover(samples);
  FitSeatedBodies();
  AimGlances();
  PlanWalkers(samples, obstacles);
  WarnIdleWalkers();
  PlanContactHeat();
  std::sort(events_.begin(), events_.end(), [](const DatasetEvent& a, const DatasetEvent& b) {
    return a.frame != b.frame ? a.frame < b.frame : a.person < b.person;
  });
}

// Seat turnover at every lap boundary the robot crosses.
void Crowd::PlanTurnover(const std::vector<RobotSample>& samples) {
  const double p = options_.turnover_probability;
  auto seat_name = [](int table, int seat) { return std::to_string(table) + "." + std::to_string(seat); };
  for (int lap = 1; p > 0 && !samples.empty() && lap <= static_cast<int>(samples.back().lap); ++lap) {
    const auto crossing =
        std::find_if(samples.begin(), samples.end(), [&](const RobotSample& s) { return s.lap >= lap; });
    const double t = crossing->time_s;
    const int frame = crossing->frame;
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
}

void Crowd::FitSeatedBodies() {
  // Elbow room on each side, now that every seat and sitter is known (people are added
  // seat by seat, so AddSeatedPerson sees only the seats before theirs).
  for (Person& person : people_) {
    if (!person.seated) continue;
    const Eigen::Matrix4d seat_from_world = person.world_from_seat.cast<double>().inverse();
    for (const Seat& other : seats_) {
      const Eigen::Vector3d at = Apply(seat_from_world, other.world_from_seat.cast<double>().topRightCorner<3, 1>());
      if (std::abs(at.x()) >= 0.35 || std::abs(at.y()) < 1e-6) continue;  // not beside them, or their own seat
      double& side = person.side_room_m[at.y() > 0 ? 0 : 1];
      side = std::min(side, 0.5 * std::abs(at.y()));
    }
  }
  // Shoulders fit between seats: where two seats beside each other stand closer than their
  // bodies' widths (as turned with their chairs) plus kSeatedShoulderGapM, bodies are no larger
  // than fits. One cap for the scene, so people keep their size when they change seats; World
  // refuses a seat spacing that leaves less than the smallest body.
  const Eigen::Vector2d half = skeleton_->UpperBodyHalfExtentM();
  double largest_scale = 1e30;
  for (size_t a = 0; a < seats_.size(); ++a) {
    for (size_t b = a + 1; b < seats_.size(); ++b) {
      const Eigen::Matrix4d sa = seats_[a].world_from_seat.cast<double>(),
                            sb = seats_[b].world_from_seat.cast<double>();
      const Eigen::Vector3d at = Apply(sa.inverse(), sb.topRightCorner<3, 1>());
      if (std::abs(at.x()) >= 0.35 || std::abs(at.y()) < 1e-6) continue;  // not beside each other
      const Eigen::Vector2d u = (sb.topRightCorner<2, 1>() - sa.topRightCorner<2, 1>()).normalized();
      // A body's reach along u. The torso's cross-section is a superellipse of exponent 2.6
      // (tools/make_assets) with these half extents: its reach is the dual norm, exponent 2.6/1.6.
      auto reach = [&](const Eigen::Matrix4d& seat) {
        constexpr double kDual = 2.6 / 1.6;
        return std::pow(std::pow(half.x() * std::abs(u.dot(seat.block<2, 1>(0, 0).normalized())), kDual) +
                            std::pow(half.y() * std::abs(u.dot(seat.block<2, 1>(0, 1).normalized())), kDual),
                        1 / kDual);
      };
      const double distance = (sb.topRightCorner<2, 1>() - sa.topRightCorner<2, 1>()).norm();
      largest_scale = std::min(largest_scale, (distance - kSeatedShoulderGapM) / (reach(sa) + reach(sb)));
    }
  }
  for (Person& person : people_) {
    if (person.seated) person.height_scale = std::min(person.height_scale, largest_scale);
  }
}

// Glances and talk go to the people at the same table when each episode starts (directions in
// the person's seat frame), whichever of them sat down first.
void Crowd::AimGlances() {
  for (Person& person : people_) {
    if (!person.seated) continue;
    const Eigen::Matrix4d seat_from_world = person.world_from_seat.cast<double>().inverse();
    for (ActivityEpisode& episode : person.activities) {
      std::vector<double> neighbours;
      for (const Person& other : people_) {
        if (!other.seated || other.table != person.table || other.person_id == person.person_id) continue;
        if (other.arrive_s > episode.start_s || other.leave_s <= episode.start_s) continue;
        const Eigen::Vector3d at = Apply(seat_from_world, other.world_from_seat.cast<double>().topRightCorner<3, 1>());
        neighbours.push_back(std::atan2(at.y(), at.x()));
      }
      GazeAt(neighbours, &episode);
    }
  }
}

// Walkers: bouts on the robot's route ahead of it (between the camera and the seated people:
// the occlusion knob), across its path and past it, clear of furniture, the robot and each other.
void Crowd::PlanWalkers(const std::vector<RobotSample>& samples, const std::vector<Obstacle2D>& obstacles) {
  const std::map<std::string, double> behaviour_weights = options_.walker_behaviours.ByName();
  walker_plans_.clear();
  for (int w = 0; w < options_.walkers; ++w) {
    Rng rng = KeyedRng(seed_, "crowd.walker", w);
    Person& walker = AddStandingPerson("walker", &rng);
    walker.walker = w;
    Dress(&walker);
    walker.lead_s = rng.Uniform(4.0, 9.0);
    walker.lead_amplitude_s = rng.Uniform(0.5, 1.5);
    walker.lead_period_s = rng.Uniform(15.0, 30.0);
    walker.lead_phase_rad = rng.Uniform(0, 2 * M_PI);
    walker.lateral_m = rng.Uniform(0.0, 0.04);  // to the left: the tables are on the right of a clockwise lap
    const auto space = WalkerSpace(samples, obstacles, kWalkerRadiusM * walker.height_scale);
    walker_plans_.push_back(
        PlanWalker(behaviour_weights, seed_, w, duration_s_, space, robot_, walker_plans_, doors_, walker.lateral_m));
  }
}

std::shared_ptr<const FreeSpace> Crowd::WalkerSpace(const std::vector<RobotSample>& samples,
                                                    const std::vector<Obstacle2D>& obstacles, double radius_m) const {
  const auto space = std::make_shared<const FreeSpace>(obstacles, radius_m);
  for (size_t d = 0; d < doors_.size(); ++d) {
    std::string nearest;
    const double clearance = space->Clearance(DoorThreshold(doors_[d], space->radius_m()), &nearest);
    if (clearance >= 0) continue;
    throw InputError(
        scene_file_,
        "/room/doors/" + std::to_string(d) + ": walkers (crowd.walkers) enter and leave the room here, but " + nearest +
            " stands in the doorway; a walker's body needs " + std::to_string(space->radius_m()).substr(0, 5) +
            " m free around it just inside: move the door or " + nearest + ", or set crowd.walkers to 0");
  }
  for (const RobotSample& s : samples) {
    const Eigen::Vector2d at(s.base.x_m, s.base.y_m);
    if (space->FreeAlong(at, Eigen::Vector2d(-std::sin(s.base.theta_rad), std::cos(s.base.theta_rad)),
                         kWalkerMaxSidestepM))
      continue;
    std::string nearest;
    const double clearance = space->Clearance(at, &nearest);
    throw InputError(scene_file_,
                     "/route/waypoints_m: walkers (crowd.walkers) follow the robot's route, which passes " +
                         std::to_string(clearance + space->radius_m()).substr(0, 5) + " m from " + nearest +
                         " at t = " + std::to_string(s.time_s).substr(0, 6) +
                         " s with no room to step aside; a walker's body needs " +
                         std::to_string(space->radius_m()).substr(0, 5) +
                         " m: move the route away from it or set crowd.walkers to 0");
  }
  return space;
}

// Walkers are planned one after another, each clear of the robot and of those before it: in
// narrow aisles the later ones find little or no time to walk. Say so rather than quietly
// rendering fewer walkers than asked for.
void Crowd::WarnIdleWalkers() {
  const int walkers = options_.walkers;
  std::vector<int> idle;
  for (int w = 0; w < walkers; ++w) {
    double in_room_s = 0;
    for (const WalkerSegment& s : walker_plans_[w].segments) {
      if (s.behaviour != "gone") in_room_s += std::max(0.0, std::min(s.end_s, duration_s_) - std::max(s.start_s, 0.0));
    }
    if (in_room_s < 0.05 * duration_s_) idle.push_back(w + 1);
  }
  if (!idle.empty()) {
    std::string which;
    for (int w : idle) which += (which.empty() ? "" : ", ") + std::to_string(w);
    warnings_.push_back(scene_file_ + ": crowd.walkers is " + std::to_string(walkers) + ", but walker" +
                        (idle.size() > 1 ? "s " : " ") + which + (idle.size() > 1 ? " are" : " is") +
                        " in the room for less than 5 % of the run: the aisles leave no clear time beside the robot "
                        "and the walkers planned before " +
                        (idle.size() > 1 ? "them" : "it") + ", so more walkers add little occlusion here");
  }
}

int Crowd::NextPersonId() const {
  int id = 0;
  for (const Person& p : people_) id = std::max(id, p.person_id + 1);
  return id;
}

Person& Crowd::AddStandingPerson(const std::string& kind, Rng* rng) {
  const int id = NextPersonId();
  Person person;
  person.person_id = id;
  person.seated = false;
  person.postures.emplace_back(0.0, "standing");
  person.height_scale = std::clamp(1.0 + options_.height_scale_sd * rng->Normal(), 0.85, 1.15);
  person.parts = AddBody(
      id, kind + " " + std::to_string(id), options_.skin_temperature_c + 0.5 * std::clamp(rng->Normal(), -2.0, 2.0),
      options_.clothing_temperature_c + 0.5 * std::clamp(rng->Normal(), -2.0, 2.0), options_.hair_temperature_c);
  person.instance = person.parts[0];
  people_.push_back(person);
  return people_.back();
}

BodyPose Crowd::PoseOf(const Person& p, double time_s, Eigen::Matrix4d* world_from_person) const {
  const double sway = sway_amplitude_rad_ * std::sin(2 * M_PI * time_s / p.sway_period_s + p.sway_phase_rad);
  const double breath = options_.breathing_amplitude_m *
                        std::sin(2 * M_PI * time_s / options_.breathing_period_s + p.breathing_phase_rad);
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
      const double w = SmoothStep((time_s - p.postures[k].first) / options_.activity.posture_blend_s);
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
  const WalkerPlacement place = PlaceWalker(plan, robot_, time_s);
  *world_from_person =
      PlacementTransform(Eigen::Vector3d(place.at_m.x(), place.at_m.y(), 0.0), place.heading_rad, p.height_scale)
          .cast<double>();
  if (place.speed_m_s < 0.03) return PresetPose("standing");
  const double stride_m = Skeleton::StrideAt(place.speed_m_s) * p.height_scale;
  const double phase = 2 * M_PI * plan.Walked(time_s) * robot_.cruise_speed_m_s() / stride_m + p.lead_phase_rad;
  // Furniture close ahead (a chair past the corner where the route turns): shorter steps, and so
  // a shorter arm swing, until neither hand's furthest reach (about a quarter of a stride ahead
  // of the pelvis, 0.2 m to its side) comes within 5 cm of a footprint. The footprint circle
  // alone leaves the swinging hands out.
  constexpr double kReachPerStride = 0.25, kHandSideM = 0.2, kHandClearanceM = 0.05;
  double pose_stride_m = stride_m;
  if (plan.space != nullptr) {
    const Eigen::Vector2d ahead(std::cos(place.heading_rad), std::sin(place.heading_rad)), left(-ahead.y(), ahead.x());
    const auto hands_clear = [&](double stride) {
      for (const double side : {-1.0, 1.0}) {
        const Eigen::Vector2d hand =
            place.at_m + kReachPerStride * stride * ahead + side * kHandSideM * p.height_scale * left;
        if (plan.space->Clearance(hand) + plan.space->radius_m() < kHandClearanceM) return false;
      }
      return true;
    };
    while (pose_stride_m > 0.3 * p.height_scale && !hands_clear(pose_stride_m)) pose_stride_m *= 0.8;
  }
  return skeleton_->Walking(phase, pose_stride_m / p.height_scale);
}

void Crowd::KeepOwnElbowRoom(const Person& p, BodyPose* pose) const {
  // Forearms are 3.5-4 cm thick in radius: their axes keep that far (and 1 cm more, for chairs
  // turned a few degrees) inside the person's half of the gap, so neighbours keep 7 cm apart.
  constexpr double kForearmRadiusM = 0.046;
  for (int s = 0; s < 2; ++s) {
    const double sign = s == 0 ? 1 : -1;
    const double limit = p.side_room_m[s] - kForearmRadiusM;
    if (limit > 0.35) continue;  // nobody close on this side
    ArmPose& arm = pose->arm[s];
    arm.wrist_m.y() = sign * std::min(sign * arm.wrist_m.y(), limit - 0.02);
    // Elbows: turned in, more the closer the neighbour, until the elbow is inside the limit.
    arm.elbow_hint.y() = -sign * std::clamp((0.30 - p.side_room_m[s]) * 5, 0.0, 0.6);
    for (int iteration = 0; iteration < 8; ++iteration) {
      const auto keypoints = skeleton_->Keypoints(skeleton_->PartTransforms(skeleton_->Limit(*pose)));
      const double out = std::max(sign * keypoints[kLeftElbow + s].y(), sign * keypoints[kLeftWrist + s].y()) - limit;
      if (out <= 0) break;
      arm.elbow_hint.y() -= sign * 0.5;
      arm.elbow_hint.x() += 0.3;  // elbow forward, in front of the chest
      arm.wrist_m.y() -= sign * std::min(out, 0.03);
    }
  }
}

double DepthIntoSlab(const Asset& part, const Eigen::Matrix4d& table_from_part, const TableSlab& slab) {
  // The moved box bounds every moved vertex (m is affine): clear of the slab, no vertex can be
  // in it (the margin covers rounding, so the answer is the vertices' own).
  Eigen::AlignedBox3d moved;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3f c = part.bounds_m.corner(static_cast<Eigen::AlignedBox3f::CornerType>(corner));
    moved.extend(Apply(table_from_part, c.cast<double>()));
  }
  constexpr double kMarginM = 1e-6;
  if (moved.max().x() + kMarginM < slab.x_min || moved.min().x() - kMarginM > slab.x_max ||
      moved.max().y() + kMarginM < slab.y_min || moved.min().y() - kMarginM > slab.y_max ||
      moved.max().z() + kMarginM < slab.z_min || moved.min().z() - kMarginM > slab.z_max) {
    return 0;
  }
  double deepest = 0;
  for (const Eigen::Vector3f& v : part.mesh.positions_m) {
    const Eigen::Vector3d q = Apply(table_from_part, v.cast<double>());
    if (q.x() > slab.x_min && q.x() < slab.x_max && q.y() > slab.y_min && q.y() < slab.y_max && q.z() < slab.z_max &&
        q.z() > slab.z_min) {
      deepest = std::max(deepest, slab.z_max - q.z());
    }
  }
  return deepest;
}

void Crowd::KeepClearOfTable(const Person& p, BodyPose* pose) const {
  // The table top slab in the table frame, grown by a few millimetres of clearance.
  constexpr double kClearanceM = 0.004;
  const Eigen::Vector3f lo = table_bounds_m_.at(p.table).min(), hi = table_bounds_m_.at(p.table).max();
  const TableSlab slab{lo.x() - kClearanceM, hi.x() + kClearanceM,        lo.y() - kClearanceM,
                       hi.y() + kClearanceM, hi.z() - 0.03 - kClearanceM, hi.z() + kClearanceM};
  // How deep the part's mesh reaches into the slab from above (0 if it does not).
  auto depth = [&](const Eigen::Matrix4d& seat_from_part, int part) {
    return DepthIntoSlab(skeleton_->part(part), p.table_from_seat * seat_from_part, slab);
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

bool Crowd::ForearmOnTable(const Person& p, const Eigen::Vector3d& wrist) {
  // Low enough to rest on the top and at least 3 cm in from its near edge (wherever the chair stands).
  return p.at_table_top && wrist.z() <= 0.80 && wrist.x() >= p.table_edge_m + 0.03;
}

BodyPose Crowd::PoseAt(const Person& p, double time_s, Eigen::Matrix4d* world_from_person,
                       Eigen::Matrix4d* seat_from_cup_out, std::string* activity) const {
  BodyPose pose = PoseOf(p, time_s, world_from_person);
  Eigen::Matrix4d seat_from_cup = Eigen::Matrix4d::Identity();
  seat_from_cup.topRightCorner<3, 1>() = p.cup_at_m;
  const auto episode = std::find_if(p.activities.begin(), p.activities.end(),
                                    [&](const ActivityEpisode& e) { return e.start_s <= time_s && time_s < e.end_s; });
  if (episode != p.activities.end()) {
    *activity = episode->name;
    const Eigen::Vector2d robot = robot_.At(time_s);
    const Eigen::Vector3d robot_in_seat =
        Apply(world_from_person->inverse(), Eigen::Vector3d(robot.x(), robot.y(), 0.0));
    // Talking: the gesturing hand on the side with more room.
    ActivityEpisode e = *episode;
    if (e.name == "talking" && p.side_room_m[e.side] < p.side_room_m[1 - e.side]) e.side = 1 - e.side;
    pose = ApplyActivity(*skeleton_, pose, e, time_s, options_.activity.blend_s, {p.cup_at_m, p.laptop_at_m},
                         std::atan2(robot_in_seat.y(), robot_in_seat.x()), &seat_from_cup);
  }
  if (p.seated) {
    KeepOwnElbowRoom(p, &pose);
    if (p.at_table_top) KeepClearOfTable(p, &pose);
  }
  *seat_from_cup_out = seat_from_cup;
  return skeleton_->Limit(pose);
}

void Crowd::SetTime(double time_s) {
  for (Person& p : people_) {
    p.present = time_s >= p.arrive_s && time_s < p.leave_s;
    // Walkers are in the room (or in a doorway) while their plan says so.
    if (p.walker >= 0) p.present = PlaceWalker(walker_plans_.at(p.walker), robot_, time_s).present;
    p.posture.clear();
    for (const auto& [from, name] : p.postures)
      if (from <= time_s) p.posture = name;
    p.activity.clear();
    p.contacts_m.clear();
    UpdateClothing(p, time_s);  // present or not, so that the state at a time is the same whatever came before
    if (!p.present) {
      for (int part : p.parts) stage_.Move(part, kHidden);
      for (int prop : {p.cup, p.laptop})
        if (prop >= 0) stage_.Move(prop, kHidden);
      continue;
    }
    Eigen::Matrix4d world_from_person, seat_from_cup;
    const BodyPose pose = PoseAt(p, time_s, &world_from_person, &seat_from_cup, &p.activity);
    if (p.walker >= 0) p.posture = walker_plans_[p.walker].At(time_s).behaviour;
    const auto parts = skeleton_->PartTransforms(pose);
    for (int i = 0; i < Skeleton::kPartCount; ++i) {
      stage_.Move(p.parts[i], (world_from_person * parts[i]).cast<float>());
    }
    const auto keypoints = skeleton_->Keypoints(parts);
    for (int k = 0; k < kCocoKeypointCount; ++k) p.keypoints_m[k] = Apply(world_from_person, keypoints[k]);
    // Contacts with the chair, the table and the floor follow the moving parts.
    if (p.seated) {
      p.contacts_m.emplace_back(
          "seat", Apply(world_from_person, Eigen::Vector3d(pose.pelvis_m.x() + 0.02, pose.pelvis_m.y(), 0.45)));
      for (int s = 0; s < 2 && p.at_table_top; ++s) {
        const Eigen::Vector3d elbow = keypoints[kLeftElbow + s], wrist = keypoints[kLeftWrist + s];
        if (!ForearmOnTable(p, wrist)) continue;
        const Eigen::Vector3d mid = 0.5 * (elbow + wrist);
        p.contacts_m.emplace_back(
            "table",
            Apply(world_from_person, Eigen::Vector3d(std::max(p.table_edge_m + 0.03, mid.x()), mid.y(), 0.74)));
      }
    }
    for (const auto& [name, at] : skeleton_->FootContacts(parts)) {
      if (at.z() < 0.02) p.contacts_m.emplace_back(name, Apply(world_from_person, at));
    }
    // Props: the cup rests or travels with the hand; the laptop faces its user.
    const Eigen::Matrix4d world_from_seat = p.world_from_seat.cast<double>();
    if (p.cup >= 0) stage_.Move(p.cup, (world_from_seat * seat_from_cup).cast<float>());
    if (p.laptop >= 0) {
      Eigen::Matrix4d seat_from_laptop = Eigen::Matrix4d::Identity();
      seat_from_laptop.topLeftCorner<3, 3>() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      seat_from_laptop.topRightCorner<3, 1>() = p.laptop_at_m;
      stage_.Move(p.laptop, (world_from_seat * seat_from_laptop).cast<float>());
    }
  }
  UpdateContactHeat(time_s);
}

}  // namespace hoilcd
