#include "hoilcd/sim/generate/generator.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>

#include <Eigen/Geometry>
#include <opencv2/imgproc.hpp>

#include "clutter.h"
#include "draw_until_valid.h"
#include "floor_plan.h"
#include "hoilcd/core/dataset/dataset_folder.h"
#include "hoilcd/core/util/file_io.h"
#include "hoilcd/core/util/random.h"
#include "hoilcd/core/util/text.h"
#include "hoilcd/sim/people/walker_planner.h"
#include "layouts.h"
#include "room_objects.h"
#include "route_laps.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;

constexpr double kGridM = 0.05;             // the reachability grid, m
constexpr uint8_t kFree = 1, kReached = 2;  // its cells: 0 blocked

double Mm(double value) { return std::round(value * 1000) / 1000; }  // positions to the millimetre
ojson Point(const Eigen::Vector2d& p) { return ojson::array({Mm(p.x()), Mm(p.y())}); }
double Yaw(double deg) { return Mm(std::remainder(deg, 360.0)); }  // in [-180, 180], deg

double Clearance(const Eigen::Vector2d& p, const std::vector<Obstacle2D>& furniture, std::string* nearest = nullptr) {
  double best = 1e30;
  for (const Obstacle2D& o : furniture) {
    const double d = DistanceToObstacle(p, o);
    if (d < best) {
      best = d;
      if (nearest) *nearest = o.name;
    }
  }
  return best;
}

bool LegClear(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const std::vector<Obstacle2D>& furniture,
              double clearance_m) {
  for (const Eigen::Vector2d& p : Along(a, b))
    if (Clearance(p, furniture) < clearance_m) return false;
  return true;
}

// The clockwise loop round the furniture, clearance_m from its outermost footprints (as close as
// the paper's route passes its tables, so the camera sees them) and never outside the layout's
// route box; a leg furniture blocks becomes the shortest free path of the walker planner
// (FreeSpace) between its ends.
std::vector<Eigen::Vector2d> PlanRoute(const Eigen::Vector4d& layout_box, const World& world, double wall_m,
                                       double clearance_m) {
  const std::vector<Obstacle2D> furniture = Furniture(world);
  // An empty room keeps the layout's box; a loop is at least kSmallestLoopM across (the robot turns).
  constexpr double kSmallestLoopM = 1.5;
  Eigen::Vector2d lo = layout_box.tail<2>(), hi = layout_box.head<2>();
  if (furniture.empty()) std::swap(lo, hi);
  for (const Obstacle2D& o : furniture) {
    for (int axis = 0; axis < 2; ++axis) {
      // The footprint's reach along the axis (a circle's radius, a rectangle's projected half sizes).
      const double reach = o.shape == Obstacle2D::Shape::kCircle
                               ? o.radius_m
                               : std::abs(std::cos(o.yaw_rad - axis * M_PI / 2)) * o.half_size_m.x() +
                                     std::abs(std::sin(o.yaw_rad - axis * M_PI / 2)) * o.half_size_m.y();
      lo[axis] = std::min(lo[axis], o.center_m[axis] - reach - clearance_m);
      hi[axis] = std::max(hi[axis], o.center_m[axis] + reach + clearance_m);
    }
  }
  for (int axis = 0; axis < 2; ++axis) {
    const double grow = std::max(0.0, 0.5 * (kSmallestLoopM - (hi[axis] - lo[axis])));
    lo[axis] -= grow;
    hi[axis] += grow;
  }
  // To the millimetre, rounded away from the furniture and in from the walls.
  auto down = [](double v) { return std::floor(v * 1000 + 1e-6) / 1000; };
  auto up = [](double v) { return std::ceil(v * 1000 - 1e-6) / 1000; };
  const Eigen::Vector4d box(std::max(down(lo.x()), up(layout_box[0])), std::max(down(lo.y()), up(layout_box[1])),
                            std::min(up(hi.x()), down(layout_box[2])), std::min(up(hi.y()), down(layout_box[3])));
  const std::vector<Eigen::Vector2d> corners = {{box[0], box[1]}, {box[0], box[3]}, {box[2], box[3]}, {box[2], box[1]}};
  std::unique_ptr<FreeSpace> space;
  std::vector<Eigen::Vector2d> route;
  for (size_t i = 0; i < corners.size(); ++i) {
    const Eigen::Vector2d& a = corners[i];
    const Eigen::Vector2d& b = corners[(i + 1) % corners.size()];
    route.push_back(a);
    if (LegClear(a, b, furniture, clearance_m)) continue;
    if (!space) space = std::make_unique<FreeSpace>(world.obstacles(), std::min(clearance_m, wall_m - 0.01));
    const std::vector<Eigen::Vector2d> path = space->ShortestPath(a, b);
    if (path.size() < 2) throw InputError("route", "a free way between the route's corners round the furniture");
    route.insert(route.end(), path.begin() + 1, path.end() - 1);
  }
  for (Eigen::Vector2d& p : route) p = Eigen::Vector2d(Mm(p.x()), Mm(p.y()));
  return route;
}

// Every object inside the room; wall-mounted ones with their backs on a wall, facing into the
// room; ceiling lights touching the ceiling (1 mm tolerance).
std::vector<std::string> ObjectProblems(const Scene& scene) {
  constexpr double kTouchM = 1e-3;
  std::vector<std::string> problems;
  AssetLibrary assets(scene.assets_dir);
  const Eigen::Vector3d room = scene.room.size_m;
  std::vector<WallPart> interior = WallParts(scene.floor, room.z());
  interior.erase(std::remove_if(interior.begin(), interior.end(), [](const WallPart& p) { return p.lintel; }),
                 interior.end());
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const ObjectSpec& o = scene.objects[i];
    if (!o.enabled) continue;
    const Asset& asset = assets.Get(o.asset);
    const std::string name = "object " + std::to_string(i) + " (" + o.asset + ")";
    const Eigen::Matrix3d rotation =
        Eigen::AngleAxisd(o.yaw_deg * M_PI / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    Eigen::AlignedBox3d box;
    for (int c = 0; c < 8; ++c) {
      box.extend(o.position_m +
                 rotation * asset.bounds_m.corner(static_cast<Eigen::AlignedBox3f::CornerType>(c)).cast<double>());
    }
    if ((box.min().array() < -kTouchM).any() || (box.max() - room).maxCoeff() > kTouchM)
      problems.push_back(name + " reaches outside the room");
    if (asset.mount == "wall") {
      // The back face's centre and the way the front faces.
      const Eigen::Vector3d back = o.position_m + rotation * Eigen::Vector3d(asset.bounds_m.min().x(), 0, 0);
      const Eigen::Vector3d front = rotation.col(0);
      const bool on_wall = (std::abs(back.x()) < kTouchM && front.x() > 0.999) ||
                           (std::abs(back.x() - room.x()) < kTouchM && front.x() < -0.999) ||
                           (std::abs(back.y()) < kTouchM && front.y() > 0.999) ||
                           (std::abs(back.y() - room.y()) < kTouchM && front.y() < -0.999);
      const bool on_interior_wall = std::any_of(interior.begin(), interior.end(), [&](const WallPart& part) {
        const Eigen::AlignedBox3d& b = part.box_m;
        const bool along_y = back.y() >= b.min().y() - kTouchM && back.y() <= b.max().y() + kTouchM;
        const bool along_x = back.x() >= b.min().x() - kTouchM && back.x() <= b.max().x() + kTouchM;
        return (along_y && std::abs(back.x() - b.max().x()) < kTouchM && front.x() > 0.999) ||
               (along_y && std::abs(back.x() - b.min().x()) < kTouchM && front.x() < -0.999) ||
               (along_x && std::abs(back.y() - b.max().y()) < kTouchM && front.y() > 0.999) ||
               (along_x && std::abs(back.y() - b.min().y()) < kTouchM && front.y() < -0.999);
      });
      if (!on_wall && !on_interior_wall)
        problems.push_back(name + " is wall-mounted but its back is not on a wall facing into the room");
    }
    if (asset.mount == "hanging" && asset.class_name != "coat" && std::abs(box.max().z() - room.z()) > kTouchM) {
      problems.push_back(name + " does not touch the ceiling");
    }
  }
  return problems;
}

// The windows of the north wall: one to three, evenly spread.
ojson Windows(double length_m, double height_m, Rng* rng) {
  const int count =
      1 + static_cast<int>(rng->UniformInt(static_cast<uint32_t>(std::clamp(static_cast<int>(length_m / 3.5), 1, 3))));
  const double width = std::min(rng->Uniform(1.2, 1.8), length_m / count - 0.4);
  ojson windows = ojson::array();
  for (int i = 0; i < count; ++i) {
    windows.push_back({{"wall", "north"},
                       {"center_m", Mm(length_m * (i + 0.5) / count)},
                       {"bottom_m", 0.9},
                       {"width_m", Mm(width)},
                       {"height_m", Mm(std::min(1.4, height_m - 1.2))}});
  }
  return windows;
}

// The floor's finish, from its own keyed stream (so the rest of a seed's room is version 2's):
// matte, or one of the glossy finishes of docs/models/sensor_and_thermal.md (ε, rms roughness).
ojson Floor(uint64_t seed, int index, const GeneratorOptions& o) {
  struct Finish {
    double emissivity, roughness_um;
  };
  static constexpr Finish kGlossy[] = {
      {0.91, 0.2}, {0.92, 0.5}, {0.93, 1.0}, {0.92, 1.5}};  // epoxy, vinyl, concrete, wood
  Rng rng = KeyedRng(seed, "generate.floor", index);
  if (rng.Uniform() >= o.glossy_floor_probability) return {{"specular", false}};
  const Finish& f = kGlossy[rng.UniformInt(4)];
  return {{"specular", true}, {"emissivity", f.emissivity}, {"roughness_um", f.roughness_um}};
}

// The crowd: who sits where (each seat taken with the room's occupancy), postures, activities,
// props, walkers and turnover drawn for the room within the crowd schema.
ojson Crowd(const Layout& layout, const GeneratorOptions& o, Rng* rng) {
  const double occupancy = rng->Uniform(o.occupancy_min, o.occupancy_max);
  ojson seating = ojson::array();
  for (size_t t = 0; t < layout.pieces.size(); ++t) {
    const Piece& piece = layout.pieces[t];
    std::vector<int> seats;
    if (piece.seats == "both_sides") seats = {0, 1, 3, 4};
    if (piece.seats != "both_sides" && piece.seats != "none")
      for (int k = 0; k < piece.seat_count; ++k) seats.push_back(k);
    for (int seat : seats)
      if (rng->Uniform() < occupancy) seating.push_back({{"table", t}, {"seat", seat}});
  }
  ojson standing = ojson::array();
  for (const StandingPerson& p : layout.standing)
    standing.push_back({{"position_m", Point(p.position_m)}, {"yaw_deg", Yaw(p.yaw_deg)}});
  ojson postures;
  for (const char* name : {"seated_upright", "seated_leaning", "seated_arms_on_table", "seated_leaning_back"})
    postures[name] = Mm(rng->Uniform(o.posture_weight_min, o.posture_weight_max));
  ojson activities;
  for (const auto& [name, spec] : ActivityOptions().activities)
    activities[name] = {
        {"weight", Mm(spec.weight * rng->Uniform(1 - o.activity_weight_spread, 1 + o.activity_weight_spread))}};
  return {{"seating", seating},
          {"standing", standing},
          {"posture_weights", postures},
          {"activities", activities},
          {"cup_fraction", layout.cup_fraction},
          {"laptop_fraction", layout.laptop_fraction},
          {"walkers", static_cast<int>(rng->UniformInt(static_cast<uint32_t>(o.walkers_max + 1)))},
          {"turnover_probability", Mm(rng->Uniform(0, o.turnover_max))}};
}

ojson Tables(const Layout& layout) {
  ojson tables = ojson::array();
  for (const Piece& p : layout.pieces) {
    ojson t = {{"center_m", Point(p.center_m)}, {"yaw_deg", Yaw(p.yaw_deg)}};
    if (!p.asset.empty()) t["asset"] = p.asset;
    if (p.seats != "both_sides") t["seats"] = p.seats;
    if (p.seat_count > 0) t["seat_count"] = p.seat_count;
    tables.push_back(t);
  }
  return tables;
}

ojson ObjectJson(const PlacedObject& o) {
  return {{"asset", o.asset},
          {"position_m", ojson::array({Mm(o.position_m.x()), Mm(o.position_m.y()), Mm(o.position_m.z())})},
          {"yaw_deg", Yaw(o.yaw_deg)}};
}

ojson Objects(const Layout& layout) {
  ojson objects = ojson::array();
  for (const PlacedObject& o : layout.objects) objects.push_back(ObjectJson(o));
  return objects;
}

// One draw of a scene: the document, with the frames still to count, the route still to plan round
// the layout's route box (its corners stand in for it) and the room objects still to place.
ojson Draw(const std::string& family, uint64_t seed, int index, const GeneratorOptions& o, Rng* rng,
           Layout* layout_out) {
  const RoomSizeRange& size = o.SizeOf(family);
  auto cm = [](double value) { return std::round(value * 100) / 100; };
  const Eigen::Vector3d room(cm(rng->Uniform(size.length_min_m, size.length_max_m)),
                             cm(rng->Uniform(size.width_min_m, size.width_max_m)),
                             cm(rng->Uniform(o.height_min_m, o.height_max_m)));
  const Layout layout = DrawLayout(family, room.head<2>(), o, rng);
  *layout_out = layout;
  const Eigen::Vector4d& box = layout.route_box_m;
  ojson options = ojson::parse(GeneratorOptions::Table().ToJson(o).dump());
  options.erase("floor");  // the building floor's options: not a room's
  // The scene's own seed (render noise, people, robot) from the run's seed and the index.
  const uint64_t scene_seed = HashCombine(HashString("generate.scene_seed"), seed, static_cast<uint64_t>(index)) >> 11;
  return {
      {"name", family + "_" + std::to_string(seed) + "_" + std::to_string(index)},
      {"description", "Generated by hoilcd generate: a " + family + " layout in a room of " + ShortestDouble(room.x()) +
                          " x " + ShortestDouble(room.y()) +
                          " m (generator.layout, generator.seed and generator.index regenerate it)."},
      {"generator",
       {{"layout", family}, {"seed", seed}, {"index", index}, {"version", kGeneratorVersion}, {"options", options}}},
      {"seed", scene_seed},
      {"frames", 1},
      {"frame_rate_hz", 25.0},
      {"room",
       {{"size_m", ojson::array({room.x(), room.y(), room.z()})},
        {"windows", Windows(room.x(), room.z(), rng)},
        {"floor", Floor(seed, index, o)}}},
      {"tables", Tables(layout)},
      {"crowd", Crowd(layout, o, rng)},
      {"objects", Objects(layout)},
      {"route",
       {{"waypoints_m", ojson::array({Point({box.x(), box.y()}), Point({box.x(), box.w()}), Point({box.z(), box.w()}),
                                      Point({box.z(), box.y()})})}}}};
}

}  // namespace

std::string FamilyOf(const std::string& layout, uint64_t seed, int index) {
  if (layout == "floor") return layout;
  const std::vector<std::string>& families = LayoutFamilies();
  if (layout == "mixed") {
    Rng rng = KeyedRng(seed, "generate.family", index);
    return families[rng.UniformInt(static_cast<uint32_t>(families.size()))];
  }
  if (std::find(families.begin(), families.end(), layout) != families.end()) return layout;
  std::string expected;
  for (const std::string& f : families) expected += f + ", ";
  throw InputError("--layout", "one of: " + expected + "mixed, floor; got '" + layout + "'");
}

std::string GeneratedSceneFileName(int index, const std::string& family) {
  char number[16];
  std::snprintf(number, sizeof(number), "%04d", index);
  return std::string("scene_") + number + "_" + family + ".json";
}

std::string SceneFileText(const nlohmann::ordered_json& scene) { return scene.dump(2) + "\n"; }

std::vector<std::string> GeneratedSceneProblems(const Scene& scene, const World& world, double wall_m,
                                                double clearance_m) {
  std::vector<std::string> problems;
  const double size_x = scene.room.size_m.x(), size_y = scene.room.size_m.y();
  const std::vector<Obstacle2D> furniture = Furniture(world);
  const std::vector<Obstacle2D> interior = InteriorWalls(world);
  // Inside the room, and apart: a chair "chair T.S" may stand under its own "table T".
  for (size_t i = 0; i < furniture.size(); ++i) {
    const Obstacle2D& a = furniture[i];
    const Eigen::Vector2d reach = a.shape == Obstacle2D::Shape::kCircle
                                      ? Eigen::Vector2d(a.radius_m, a.radius_m)
                                      : Eigen::Vector2d(std::abs(std::cos(a.yaw_rad)) * a.half_size_m.x() +
                                                            std::abs(std::sin(a.yaw_rad)) * a.half_size_m.y(),
                                                        std::abs(std::sin(a.yaw_rad)) * a.half_size_m.x() +
                                                            std::abs(std::cos(a.yaw_rad)) * a.half_size_m.y());
    if ((a.center_m - reach).minCoeff() < 0 || a.center_m.x() + reach.x() > size_x ||
        a.center_m.y() + reach.y() > size_y) {
      problems.push_back(a.name + " reaches outside the room");
    }
    for (size_t j = i + 1; j < furniture.size(); ++j) {
      const Obstacle2D& b = furniture[j];
      auto own_table = [](const Obstacle2D& chair, const Obstacle2D& table) {
        return chair.name.rfind("chair ", 0) == 0 && table.name.rfind("table ", 0) == 0 &&
               chair.name.substr(6, chair.name.find('.') - 6) == table.name.substr(6);
      };
      if (own_table(a, b) || own_table(b, a)) continue;
      if (FootprintsOverlap(a, b)) problems.push_back(a.name + " overlaps " + b.name);
    }
  }
  // The route: a closed clockwise loop keeping its distances.
  const std::vector<Eigen::Vector2d>& route = scene.route.waypoints_m;
  double twice_area = 0;
  for (size_t i = 0; i < route.size(); ++i) {
    const Eigen::Vector2d& a = route[i];
    const Eigen::Vector2d& b = route[(i + 1) % route.size()];
    twice_area += a.x() * b.y() - b.x() * a.y();
    for (const Eigen::Vector2d& p : Along(a, b)) {
      std::string nearest;
      const double clearance = Clearance(p, furniture, &nearest);
      if (clearance < clearance_m - 1e-6) {
        problems.push_back("the route passes " + ShortestDouble(Mm(clearance)) + " m from " + nearest + " on leg " +
                           std::to_string(i));
        break;
      }
      if (std::min({p.x(), p.y(), size_x - p.x(), size_y - p.y(), Clearance(p, interior)}) < wall_m - 1e-6) {
        problems.push_back("the route comes closer than " + ShortestDouble(wall_m) + " m to a wall on leg " +
                           std::to_string(i));
        break;
      }
    }
  }
  if (route.size() < 3 || twice_area >= 0) problems.push_back("the route is not a closed clockwise loop");
  for (const std::string& p : ObjectProblems(scene)) problems.push_back(p);
  // Reachability: the floor a person fits on, as a 5 cm grid, flooded from the route's start.
  const int nx = static_cast<int>(size_x / kGridM), ny = static_cast<int>(size_y / kGridM);
  cv::Mat floor(ny, nx, CV_8U, cv::Scalar(0));
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const Eigen::Vector2d p((i + 0.5) * kGridM, (j + 0.5) * kGridM);
      const bool in_room = std::min({p.x(), p.y(), size_x - p.x(), size_y - p.y()}) >= kAccessRadiusM;
      if (in_room && Clearance(p, furniture) >= kAccessRadiusM && Clearance(p, interior) >= kAccessRadiusM)
        floor.at<uint8_t>(j, i) = kFree;
    }
  }
  auto cell_of = [&](const Eigen::Vector2d& p) {
    return cv::Point(std::clamp(static_cast<int>(p.x() / kGridM), 0, nx - 1),
                     std::clamp(static_cast<int>(p.y() / kGridM), 0, ny - 1));
  };
  if (!route.empty() && floor.at<uint8_t>(cell_of(route.front())) == kFree) {
    cv::floodFill(floor, cell_of(route.front()), cv::Scalar(kReached), nullptr, cv::Scalar(0), cv::Scalar(0), 4);
  }
  const std::vector<Eigen::Vector2d> access = SeatAccess(world);
  const std::vector<Crowd::SeatPlace> seats = world.seat_places();
  for (size_t k = 0; k < access.size(); ++k) {
    const Crowd::SeatPlace& seat = seats[k];
    if (floor.at<uint8_t>(cell_of(access[k])) != kReached) {
      problems.push_back("seat " + std::to_string(seat.table) + "." + std::to_string(seat.seat) +
                         " cannot be reached on foot from the route");
    }
  }
  return problems;
}

ojson GenerateScene(const std::string& layout, uint64_t seed, int index, const GeneratorOptions& options) {
  if (layout == "floor") return GenerateFloorScene(seed, index, options);
  const std::string family = FamilyOf(layout, seed, index);
  const std::string where = "scene " + std::to_string(index) + " (" + family + ")";
  return DrawUntilValid(where, "scene", options.attempts, [&](int attempt, std::string* problem) {
    Rng rng = KeyedRng(seed, "generate.scene", index, HashString(family), attempt);
    Layout layout;
    ojson doc = Draw(family, seed, index, options, &rng, &layout);
    Scene scene = SceneFromJson(nlohmann::json::parse(doc.dump()), where);
    const BandRadianceTable table;
    const World world(scene, table);
    const std::vector<Eigen::Vector2d> route =
        PlanRoute(layout.route_box_m, world, options.route_wall_m, options.route_clearance_m);
    // The room's fittings and people's things, from their own stream: the furniture a draw
    // gives does not depend on them.
    Rng things_rng = KeyedRng(seed, "generate.objects", index, HashString(family), attempt);
    const Eigen::Vector3d room = scene.room.size_m;
    const bool whiteboard = HasFrontWall(family) && things_rng.Uniform() < options.objects.whiteboard_probability;
    const std::vector<Eigen::Vector2d> doors = RoomDoors(room.head<2>(), whiteboard);
    const RoomContext context{layout, doors, world, route, options, &things_rng};
    std::vector<PlacedObject> added = RoomFittings(room, doc["room"]["windows"], whiteboard, context);
    std::vector<std::pair<int, int>> occupied;
    for (const ojson& s : doc["crowd"]["seating"]) occupied.emplace_back(s["table"].get<int>(), s["seat"].get<int>());
    for (const PlacedObject& o : PeoplesThings(occupied, room.head<2>(), context)) added.push_back(o);
    // The clutter, from its own stream: at density 0 the room is what it was without it.
    Rng clutter_rng = KeyedRng(seed, "generate.clutter", index, HashString(family), attempt);
    std::vector<PlacedObject> so_far = layout.objects;
    so_far.insert(so_far.end(), added.begin(), added.end());
    AssetLibrary assets(scene.assets_dir);
    for (const PlacedObject& o :
         Clutter(room, layout, doc["room"]["windows"], doors, so_far, world, &assets, route, options, &clutter_rng))
      added.push_back(o);
    doc["room"]["doors"] = ojson::array();
    for (const Eigen::Vector2d& d : doors) doc["room"]["doors"].push_back({{"position_m", Point(d)}});
    // With every object, else without the floor-standing ones and what stands on them (bags,
    // cabinets, bookcases and their books, PCs, bins, boxes: the only ones that can block a seat's
    // access the checks below find).
    std::vector<std::string> problems;
    bool placed = false;
    for (const bool floor : {true, false}) {
      ojson candidate = doc;
      for (const PlacedObject& o : added)
        if (floor || !StandsOnTheFloor(o.asset)) candidate["objects"].push_back(ObjectJson(o));
      Scene final_scene = SceneFromJson(nlohmann::json::parse(candidate.dump()), where);
      final_scene.route.waypoints_m = route;
      const World final_world(final_scene, table);
      problems = GeneratedSceneProblems(final_scene, final_world, options.route_wall_m, options.route_clearance_m);
      if (!problems.empty()) continue;
      doc = candidate;
      doc["frames"] = FramesForLaps(final_scene, final_world, route, options.laps);
      placed = true;
      break;
    }
    if (!placed) {
      *problem = problems.front();
      return ojson();
    }
    doc["route"]["waypoints_m"] = ojson::array();
    for (const Eigen::Vector2d& p : route) doc["route"]["waypoints_m"].push_back(Point(p));
    return doc;  // DrawUntilValid then checks what `hoilcd validate` does
  });
}

void CheckGenerateFolder(const std::string& dir) {
  std::error_code ec;
  if (!fs::exists(dir, ec)) {
    if (ec) throw InputError(dir, "cannot check the folder (" + ec.message() + ")");
    return;
  }
  if (!fs::is_directory(dir, ec)) {
    throw InputError(dir, "is a file: expected a folder (new, empty, or holding scenes hoilcd generate wrote)");
  }
  std::vector<std::string> others;
  for (const std::string& name : ListFolder(dir)) {  // a folder it cannot list is refused, not taken as empty
    const fs::path path = fs::path(dir) / name;
    bool ours = false;
    if (fs::is_regular_file(path, ec) && path.extension() == ".json" && fs::file_size(path, ec) < (64u << 20)) {
      const nlohmann::json doc = nlohmann::json::parse(ReadFileBytes(path.string()), nullptr, false);
      ours = doc.is_object() && doc.contains("generator") && doc["generator"].is_object();
    }
    if (!ours) others.push_back(name);
  }
  if (!others.empty()) {
    throw InputError(dir, "holds files that are not scenes hoilcd generate wrote (" + JoinFileList(others) +
                              "); refusing to write among them: choose a new or empty folder");
  }
}

}  // namespace hoilcd
