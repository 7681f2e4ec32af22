// `hoilcd generate --layout floor`: a building floor made of generated rooms. Rooms of the six
// families (drawn per place, among those whose width range holds the row's depth) stand side by
// side along both sides of a corridor, the south row turned half round so every room's windows are
// on an outside wall and its own south wall faces the corridor. Each room gets two doorways onto
// the corridor, at its route's west and east legs; the route drives the corridor eastwards in its
// north lane, entering each north room by its west doorway, round its furniture and out by its
// east one, turns in the corridor's east end and comes back westwards through the south rooms.
#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Geometry>

#include "draw_until_valid.h"
#include "floor_plan.h"
#include "hoilcd/core/util/random.h"
#include "hoilcd/core/util/text.h"
#include "hoilcd/sim/generate/generator.h"
#include "hoilcd/sim/robot/robot.h"
#include "route_laps.h"

namespace hoilcd {
namespace {

using ojson = nlohmann::ordered_json;

constexpr double kLaneFromWallM = 0.6;  // the route's lanes from the corridor's walls, m
constexpr double kTurnFromEndM = 0.9;   // the route's turns from the corridor's end walls, m
constexpr double kLobbyM = 2.0;         // open floor at each end of the corridor, beyond the rows, m

double Mm(double value) { return std::round(value * 1000) / 1000; }
ojson Point(const Eigen::Vector2d& p) { return ojson::array({Mm(p.x()), Mm(p.y())}); }
Eigen::Vector2d Vec2(const ojson& j) { return {j.at(0).get<double>(), j.at(1).get<double>()}; }

// Where a generated room stands: room frame to floor frame (a shift, and half a turn for the south row).
struct Placement {
  Eigen::Vector2d origin_m;  // the room's (0, 0) corner in the floor... or, turned, its (length, width) corner
  bool turned = false;
  Eigen::Vector2d size_m;
  Eigen::Vector2d Apply(const Eigen::Vector2d& p) const {
    return turned ? Eigen::Vector2d(origin_m + size_m - p) : Eigen::Vector2d(origin_m + p);
  }
  double Yaw(double yaw_deg) const { return Mm(std::remainder(yaw_deg + (turned ? 180.0 : 0.0), 360.0)); }
};

// One generated room of the floor and its place.
struct PlacedRoom {
  std::string family;
  ojson scene;
  Placement where;
  double door_a_m = 0, door_b_m = 0;  // doorway centres along the room's south wall (room frame)
};

// The families whose width range holds the depth, in LayoutFamilies' order.
std::vector<std::string> FamiliesFor(double depth_m, const GeneratorOptions& o) {
  std::vector<std::string> out;
  for (const std::string& f : LayoutFamilies()) {
    const RoomSizeRange& r = o.SizeOf(f);
    if (r.width_min_m <= depth_m + 1e-9 && depth_m <= r.width_max_m + 1e-9) out.push_back(f);
  }
  return out;
}

// A generated room of `family`, depth_m deep, at most room_length_max_m long, the floor's height,
// without walkers or turnover of its own.
ojson DrawRoom(const std::string& family, double depth_m, uint64_t seed, int slot, const GeneratorOptions& o) {
  GeneratorOptions room = o;
  RoomSizeRange& size = const_cast<RoomSizeRange&>(room.SizeOf(family));
  size.width_min_m = size.width_max_m = depth_m;
  size.length_max_m = std::min(size.length_max_m, o.floor.room_length_max_m);
  size.length_min_m = std::min(size.length_min_m, size.length_max_m);
  room.height_min_m = room.height_max_m = o.floor.height_m;
  room.walkers_max = 0;
  room.turnover_max = 0;
  return GenerateScene(family, seed, slot, room);
}

// The doorways' centres along the room's south wall: at the route's west and east legs, kept
// within the wall.
void PlaceDoors(PlacedRoom* room, const GeneratorOptions& o) {
  double west = 1e30, east = -1e30;
  for (const ojson& p : room->scene["route"]["waypoints_m"]) {
    west = std::min(west, p[0].get<double>());
    east = std::max(east, p[0].get<double>());
  }
  const double half = 0.5 * o.floor.door_width_m + 0.1, length = room->where.size_m.x();
  room->door_a_m = Mm(std::clamp(west, half, length - half));
  room->door_b_m = Mm(std::clamp(east, half, length - half));
  if (room->door_b_m - room->door_a_m < o.floor.door_width_m + 0.2) {
    throw InputError("floor", "a room long enough for two doorways on its corridor wall");
  }
}

// Whether a room object stays: its own doorways' frames and switches go (its doorways are now the
// corridor's), and so does anything within reach of the new doorways; bags go too (placed beside
// chairs whose jitter, keyed by the table's index, differs on the floor).
bool KeepObject(const ojson& object, const PlacedRoom& room, double door_width_m) {
  const std::string asset = object["asset"].get<std::string>();
  if (asset == "door_frame" || asset == "light_switch" || asset == "bag") return false;
  const Eigen::Vector2d p = Vec2(object["position_m"]);
  for (double door : {room.door_a_m, room.door_b_m}) {
    if (std::abs(p.x() - door) < 0.5 * door_width_m + 0.9 && p.y() < 1.0) return false;
  }
  return true;
}

// The room's part of the route, in the room frame: from its lane in the corridor (y < 0) in
// through doorway A, clockwise round the furniture (the room's own route from its south-west
// corner to its south-east one) and out through doorway B back to the lane.
std::vector<Eigen::Vector2d> RoomVisit(const PlacedRoom& room, double lane_y) {
  std::vector<Eigen::Vector2d> loop;
  for (const ojson& p : room.scene["route"]["waypoints_m"]) loop.push_back(Vec2(p));
  double south = 1e30, east = -1e30;
  for (const Eigen::Vector2d& p : loop) {
    south = std::min(south, p.y());
    east = std::max(east, p.x());
  }
  size_t last = 0;  // the south-east corner: the loop's last point on its south and east legs
  for (size_t i = 0; i < loop.size(); ++i)
    if (std::abs(loop[i].x() - east) < 1e-9 && std::abs(loop[i].y() - south) < 1e-9) last = i;
  const double inside = std::min(south, 0.6);
  std::vector<Eigen::Vector2d> visit = {{room.door_a_m, lane_y}, {room.door_a_m, inside}};
  visit.insert(visit.end(), loop.begin(), loop.begin() + static_cast<long>(last) + 1);
  visit.push_back({room.door_b_m, inside});
  visit.push_back({room.door_b_m, lane_y});
  return visit;
}

// Drops repeated points and points on a straight line between their neighbours.
std::vector<Eigen::Vector2d> Simplified(const std::vector<Eigen::Vector2d>& route) {
  std::vector<Eigen::Vector2d> out;
  for (const Eigen::Vector2d& p : route) {
    const Eigen::Vector2d q(Mm(p.x()), Mm(p.y()));
    if (!out.empty() && (out.back() - q).norm() < 1e-6) continue;
    out.push_back(q);
  }
  while (out.size() > 1 && (out.back() - out.front()).norm() < 1e-6) out.pop_back();
  for (bool removed = true; removed;) {
    removed = false;
    for (size_t i = 0; i < out.size() && out.size() > 3; ++i) {
      const Eigen::Vector2d& a = out[(i + out.size() - 1) % out.size()];
      const Eigen::Vector2d& b = out[(i + 1) % out.size()];
      const Eigen::Vector2d ab = b - a, ap = out[i] - a;
      if (std::abs(ab.x() * ap.y() - ab.y() * ap.x()) < 1e-9 && ap.dot(ab) > 0 && ap.norm() < ab.norm()) {
        out.erase(out.begin() + static_cast<long>(i));
        removed = true;
        break;
      }
    }
  }
  return out;
}

// What the room checks do not see of a floor: the route keeps wall_m from the interior walls
// (through the doorways' middles) and enters every room.
std::vector<std::string> FloorRouteProblems(const Scene& scene, double wall_m) {
  std::vector<std::string> problems;
  const std::vector<Eigen::Vector2d>& route = scene.route.waypoints_m;
  for (size_t i = 0; i < route.size(); ++i) {
    const int wall =
        WallCrossedBy(scene.floor, route[i], route[(i + 1) % route.size()], wall_m - 1e-6, scene.room.size_m.z());
    if (wall >= 0)
      problems.push_back("the route comes closer than " + ShortestDouble(wall_m) + " m to interior wall " +
                         std::to_string(wall) + " on leg " + std::to_string(i));
  }
  for (const FloorRoom& room : scene.floor.rooms) {
    if (room.corridor) continue;
    if (std::none_of(route.begin(), route.end(), [&](const Eigen::Vector2d& p) { return room.box_m.contains(p); })) {
      problems.push_back("the route does not enter " + room.name);
    }
  }
  return problems;
}

// The floor's rooms in two rows, each listed west to east.
struct FloorRows {
  std::vector<PlacedRoom> south, north;
  const std::vector<PlacedRoom>& Row(int row) const { return row == 0 ? south : north; }
  std::vector<PlacedRoom>& Row(int row) { return row == 0 ? south : north; }
  // The rooms in the route's order: the north row west to east, then the south row east to west.
  std::vector<PlacedRoom> RouteOrder() const {
    std::vector<PlacedRoom> ordered = north;
    for (auto it = south.rbegin(); it != south.rend(); ++it) ordered.push_back(*it);
    return ordered;
  }
};

// Where the floor's parts lie, m: across the rows (y) from the south outside wall, and along them (x).
struct FloorGeometry {
  double t = 0;                                                      // the walls' thickness
  double corridor_y0 = 0, corridor_y1 = 0;                           // the corridor's floor
  double north_y0 = 0;                                               // the north rooms' south side
  std::array<double, 2> row_end = {0, 0};                            // south, north: x of the row's east end
  double length = 0, width = 0;                                      // the whole floor
  double RowY0(int row) const { return row == 0 ? 0.0 : north_y0; }  // the row's rooms' y origin
};

// The room of slot s (the route's order: the north row west to east for s < n, then the south row
// east to west), its family drawn among those that fit the row's depth.
PlacedRoom DrawSlot(uint64_t rooms_seed, int s, const GeneratorOptions& o) {
  const bool is_north = s < o.floor.rooms_per_side;
  const double depth = is_north ? o.floor.north_depth_m : o.floor.south_depth_m;
  const std::vector<std::string> families = FamiliesFor(depth, o);
  if (families.empty())
    throw InputError("--set floor." + std::string(is_north ? "north" : "south") + "_depth_m",
                     "a depth some family's width range holds");
  Rng rng = KeyedRng(rooms_seed, "generate.floor.family", s);
  PlacedRoom room;
  room.family = families[rng.UniformInt(static_cast<uint32_t>(families.size()))];
  room.scene = DrawRoom(room.family, depth, rooms_seed, s, o);
  const ojson& size = room.scene["room"]["size_m"];
  room.where.size_m = Eigen::Vector2d(size[0].get<double>(), size[1].get<double>());
  return room;
}

FloorRows DrawRows(uint64_t rooms_seed, const GeneratorOptions& o) {
  FloorRows rows;
  const int n = o.floor.rooms_per_side;
  for (int s = 0; s < 2 * n; ++s) (s < n ? rows.north : rows.south).push_back(DrawSlot(rooms_seed, s, o));
  // South rooms in the route's order run east to west; lay both rows out west to east.
  std::reverse(rows.south.begin(), rows.south.end());
  return rows;
}

// Places both rows side by side from the west lobby (the south row turned half round) with their
// doorways, and measures the floor.
FloorGeometry PlaceRows(FloorRows* rows, const GeneratorOptions& o) {
  const FloorLayoutOptions& f = o.floor;
  FloorGeometry g;
  g.t = f.wall_thickness_m;
  g.corridor_y0 = f.south_depth_m + g.t;
  g.corridor_y1 = g.corridor_y0 + f.corridor_width_m;
  g.north_y0 = g.corridor_y1 + g.t;
  for (int row = 0; row < 2; ++row) {
    double x = kLobbyM + g.t;
    for (PlacedRoom& room : rows->Row(row)) {
      room.where.turned = row == 0;
      room.where.origin_m = Eigen::Vector2d(x, g.RowY0(row));
      PlaceDoors(&room, o);
      x += room.where.size_m.x() + g.t;
    }
    g.row_end[static_cast<size_t>(row)] = x - g.t;
  }
  g.length = Mm(std::max(g.row_end[0], g.row_end[1]) + g.t + kLobbyM);
  g.width = Mm(g.north_y0 + f.north_depth_m);
  return g;
}

// A row's corridor wall with its rooms' doorways, its west end wall and the wall east of each room.
void AddRowWalls(const std::vector<PlacedRoom>& line, int row, const FloorGeometry& g, const FloorLayoutOptions& f,
                 ojson* walls) {
  const double t = g.t;
  const double wall_y = row == 0 ? f.south_depth_m + 0.5 * t : g.north_y0 - 0.5 * t;
  const double far_y = row == 0 ? 0.0 : g.width;
  ojson doors = ojson::array();
  for (const PlacedRoom& room : line) {
    for (double along : {room.door_a_m, room.door_b_m}) {
      const double x = room.where.Apply({along, 0}).x();
      doors.push_back({{"center_m", Mm(x - kLobbyM)}, {"width_m", f.door_width_m}});  // from the wall's west end
    }
  }
  std::sort(doors.begin(), doors.end(),
            [](const ojson& a, const ojson& b) { return a["center_m"].get<double>() < b["center_m"].get<double>(); });
  const double end = g.row_end[static_cast<size_t>(row)] + t;
  walls->push_back(
      {{"from_m", Point({kLobbyM, wall_y})}, {"to_m", Point({end, wall_y})}, {"thickness_m", t}, {"doors", doors}});
  walls->push_back({{"from_m", Point({kLobbyM + 0.5 * t, far_y})},
                    {"to_m", Point({kLobbyM + 0.5 * t, wall_y})},
                    {"thickness_m", t}});
  for (const PlacedRoom& room : line) {
    const double x = room.where.origin_m.x() + room.where.size_m.x() + 0.5 * t;
    walls->push_back({{"from_m", Point({x, far_y})}, {"to_m", Point({x, wall_y})}, {"thickness_m", t}});
  }
}

// What the floor's rooms hold, gathered in the floor's frame.
struct FloorContents {
  ojson rooms = ojson::array(), walls = ojson::array(), tables = ojson::array(), objects = ojson::array();
  ojson seating = ojson::array(), standing = ojson::array(), windows = ojson::array();
  double cups = 0, laptops = 0;  // the rooms' mean cup and laptop fractions
};

// The room's tables and the objects it keeps, in the floor's frame.
void AddFurniture(const PlacedRoom& room, double door_width_m, FloorContents* out) {
  const Placement& w = room.where;
  for (ojson table : room.scene["tables"]) {
    table["center_m"] = Point(w.Apply(Vec2(table["center_m"])));
    table["yaw_deg"] = w.Yaw(table["yaw_deg"].get<double>());
    out->tables.push_back(table);
  }
  for (ojson object : room.scene["objects"]) {
    if (!KeepObject(object, room, door_width_m)) continue;
    const Eigen::Vector2d p = w.Apply(Vec2(object["position_m"]));
    object["position_m"] = ojson::array({Mm(p.x()), Mm(p.y()), object["position_m"][2]});
    object["yaw_deg"] = w.Yaw(object["yaw_deg"].get<double>());
    out->objects.push_back(object);
  }
}

// The room's seated people (at its tables, numbered after those before it) and people standing,
// in the floor's frame; its share of the cup and laptop fractions.
void AddPeople(const PlacedRoom& room, int table_base, size_t room_count, FloorContents* out) {
  const Placement& w = room.where;
  const ojson& crowd = room.scene["crowd"];
  for (ojson s : crowd["seating"]) {
    s["table"] = s["table"].get<int>() + table_base;
    out->seating.push_back(s);
  }
  for (ojson s : crowd["standing"]) {
    s["position_m"] = Point(w.Apply(Vec2(s["position_m"])));
    s["yaw_deg"] = w.Yaw(s["yaw_deg"].get<double>());
    out->standing.push_back(s);
  }
  out->cups += crowd["cup_fraction"].get<double>() / room_count;
  out->laptops += crowd["laptop_fraction"].get<double>() / room_count;
}

// The room's windows on the floor's outside wall beside it.
void AddWindows(const PlacedRoom& room, FloorContents* out) {
  const Placement& w = room.where;
  for (ojson window : room.scene["room"]["windows"]) {
    const double c = window["center_m"].get<double>();
    window["wall"] = w.turned ? "south" : "north";
    window["center_m"] = Mm(w.turned ? w.origin_m.x() + w.size_m.x() - c : w.origin_m.x() + c);
    out->windows.push_back(window);
  }
}

// The room's entry in /floor/rooms and everything it holds, in the floor's frame.
void AddRoom(const PlacedRoom& room, size_t room_count, double door_width_m, FloorContents* out) {
  const Placement& w = room.where;
  const Eigen::Vector2d lo = w.Apply({0, 0}), hi = w.Apply(w.size_m);
  out->rooms.push_back({{"name", room.family + " " + std::to_string(out->rooms.size())},
                        {"kind", "room"},
                        {"layout", room.family},
                        {"min_m", Point(lo.cwiseMin(hi))},
                        {"max_m", Point(lo.cwiseMax(hi))}});
  const int table_base = static_cast<int>(out->tables.size());
  AddFurniture(room, door_width_m, out);
  AddPeople(room, table_base, room_count, out);
  AddWindows(room, out);
}

// The corridor, and the lobbies beyond each row's ends, open to it.
void AddCorridor(const FloorGeometry& g, ojson* rooms) {
  rooms->push_back({{"name", "corridor"},
                    {"kind", "corridor"},
                    {"min_m", Point({0, g.corridor_y0})},
                    {"max_m", Point({g.length, g.corridor_y1})}});
  for (int row = 0; row < 2; ++row) {
    const double y0 = row == 0 ? 0.0 : g.corridor_y1, y1 = row == 0 ? g.corridor_y0 : g.width;
    const std::string side = row == 0 ? "south" : "north";
    rooms->push_back({{"name", "west " + side + " lobby"},
                      {"kind", "corridor"},
                      {"min_m", Point({0, y0})},
                      {"max_m", Point({kLobbyM, y1})}});
    rooms->push_back({{"name", "east " + side + " lobby"},
                      {"kind", "corridor"},
                      {"min_m", Point({g.row_end[static_cast<size_t>(row)] + g.t, y0})},
                      {"max_m", Point({g.length, y1})}});
  }
}

// The route (before Simplified): eastwards in the corridor's north lane, through each north room,
// the turn at the corridor's east end, westwards in the south lane through each south room.
std::vector<Eigen::Vector2d> FloorRoute(const std::vector<PlacedRoom>& ordered, int rooms_per_side,
                                        const FloorGeometry& g) {
  const double north_lane = g.corridor_y1 - kLaneFromWallM, south_lane = g.corridor_y0 + kLaneFromWallM;
  const double lane_y = -(g.t + kLaneFromWallM);  // in a room's frame: the corridor is below its south wall
  std::vector<Eigen::Vector2d> route = {{kTurnFromEndM, north_lane}};
  for (size_t i = 0; i < ordered.size(); ++i) {
    for (const Eigen::Vector2d& p : RoomVisit(ordered[i], lane_y)) route.push_back(ordered[i].where.Apply(p));
    if (i + 1 == static_cast<size_t>(rooms_per_side)) {
      route.push_back({g.length - kTurnFromEndM, north_lane});
      route.push_back({g.length - kTurnFromEndM, south_lane});
    }
  }
  route.push_back({kTurnFromEndM, south_lane});
  return route;
}

// The floor's crowd: the first room's settings with every room's people, their mean cup and
// laptop fractions, no walkers and the floor's turnover.
ojson FloorCrowd(const ojson& first_crowd, const FloorContents& c, double turnover_probability) {
  ojson crowd = first_crowd;
  crowd["seating"] = c.seating;
  crowd["standing"] = c.standing;
  crowd["cup_fraction"] = Mm(c.cups);
  crowd["laptop_fraction"] = Mm(c.laptops);
  crowd["walkers"] = 0;
  crowd["turnover_probability"] = turnover_probability;
  return crowd;
}

std::string FloorDescription(const std::vector<PlacedRoom>& ordered, double corridor_m, const FloorGeometry& g) {
  std::string families;
  for (const PlacedRoom& room : ordered) families += (families.empty() ? "" : ", ") + room.family;
  return "Generated by hoilcd generate --layout floor: " + std::to_string(ordered.size()) + " rooms (" + families +
         ") along a " + ShortestDouble(corridor_m) + " m corridor, " + ShortestDouble(g.length) + " x " +
         ShortestDouble(g.width) + " m (generator.seed and generator.index regenerate it).";
}

// One draw of the floor (attempt keys every room's draw).
ojson DrawFloor(uint64_t seed, int index, int attempt, const GeneratorOptions& o) {
  const FloorLayoutOptions& f = o.floor;
  const uint64_t rooms_seed = HashCombine(HashString("generate.floor.rooms"), seed, static_cast<uint64_t>(index),
                                          static_cast<uint64_t>(attempt)) >>
                              11;
  FloorRows rows = DrawRows(rooms_seed, o);
  const FloorGeometry g = PlaceRows(&rows, o);
  FloorContents contents;
  for (int row = 0; row < 2; ++row) AddRowWalls(rows.Row(row), row, g, f, &contents.walls);
  const std::vector<PlacedRoom> ordered = rows.RouteOrder();
  for (const PlacedRoom& room : ordered) AddRoom(room, ordered.size(), f.door_width_m, &contents);
  AddCorridor(g, &contents.rooms);
  const ojson& first = ordered.front().scene;
  ojson options = ojson::parse(GeneratorOptions::Table().ToJson(o).dump());
  const uint64_t scene_seed = HashCombine(HashString("generate.scene_seed"), seed, static_cast<uint64_t>(index)) >> 11;
  ojson route_json = ojson::array();
  for (const Eigen::Vector2d& p : Simplified(FloorRoute(ordered, f.rooms_per_side, g))) route_json.push_back(Point(p));
  const double corridor_mid_y = 0.5 * (g.corridor_y0 + g.corridor_y1);
  return {
      {"name", "floor_" + std::to_string(seed) + "_" + std::to_string(index)},
      {"description", FloorDescription(ordered, f.corridor_width_m, g)},
      {"generator",
       {{"layout", "floor"}, {"seed", seed}, {"index", index}, {"version", kGeneratorVersion}, {"options", options}}},
      {"seed", scene_seed},
      {"frames", 1},
      {"frame_rate_hz", 25.0},
      {"room",
       {{"size_m", ojson::array({g.length, g.width, f.height_m})},
        {"windows", contents.windows},
        {"floor", first["room"]["floor"]},
        {"doors", ojson::array({{{"position_m", Point({0, corridor_mid_y})}, {"width_m", 1.2}},
                                {{"position_m", Point({g.length, corridor_mid_y})}, {"width_m", 1.2}}})}}},
      {"floor", {{"rooms", contents.rooms}, {"walls", contents.walls}}},
      {"tables", contents.tables},
      {"crowd", FloorCrowd(first["crowd"], contents, f.turnover_probability)},
      {"objects", contents.objects},
      {"route", {{"waypoints_m", route_json}}}};
}

}  // namespace

ojson GenerateFloorScene(uint64_t seed, int index, const GeneratorOptions& options) {
  const std::string where = "scene " + std::to_string(index) + " (floor)";
  return DrawUntilValid(where, "floor", options.attempts, [&](int attempt, std::string* problem) {
    ojson doc = DrawFloor(seed, index, attempt, options);
    Scene scene = SceneFromJson(nlohmann::json::parse(doc.dump()), where);
    const BandRadianceTable table;
    const World world(scene, table);
    // The rooms' routes kept route_clearance_m from their chairs; a chair's jitter is keyed by its
    // table's index, which is another on the floor, so it may stand up to chair_jitter_m nearer.
    const double clearance_m = options.route_clearance_m - scene.furniture.chair_jitter_m;
    std::vector<std::string> problems = GeneratedSceneProblems(scene, world, options.route_wall_m, clearance_m);
    for (const std::string& p : FloorRouteProblems(scene, options.route_wall_m)) problems.push_back(p);
    if (!problems.empty()) {
      *problem = problems.front();
      return ojson();
    }
    doc["frames"] = FramesForLaps(scene, world, scene.route.waypoints_m, options.laps);
    return doc;
  });
}

}  // namespace hoilcd
