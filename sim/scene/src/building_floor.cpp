#include "hoilcd/sim/scene/building_floor.h"

#include <algorithm>
#include <cmath>
#include <deque>

#include <nlohmann/json.hpp>

#include "hoilcd/core/util/text.h"

namespace hoilcd {
namespace {

using nlohmann::json;

constexpr double kToleranceM = 1e-3;  // positions closer than this are the same

Eigen::Vector2d Vec2(const json& j) { return {j.at(0).get<double>(), j.at(1).get<double>()}; }

std::string Point(const Eigen::Vector2d& p) { return "(" + ShortestDouble(p.x()) + ", " + ShortestDouble(p.y()) + ")"; }

// The axis a wall runs along (0: x, 1: y).
int AxisOf(const InteriorWall& w) {
  return std::abs(w.to_m.y() - w.from_m.y()) <= std::abs(w.to_m.x() - w.from_m.x()) ? 0 : 1;
}

// Where a doorway's opening starts and ends along the wall's axis (world coordinate, lo < hi).
std::pair<double, double> DoorSpan(const InteriorWall& w, const FloorDoor& d) {
  const int axis = AxisOf(w);
  const double sign = w.to_m[axis] >= w.from_m[axis] ? 1.0 : -1.0;
  const double c = w.from_m[axis] + sign * d.center_m;
  return {c - 0.5 * d.width_m, c + 0.5 * d.width_m};
}

}  // namespace

bool SegmentMeetsBox(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::AlignedBox2d& box) {
  double t0 = 0, t1 = 1;
  const Eigen::Vector2d d = b - a;
  for (int axis = 0; axis < 2; ++axis) {
    if (std::abs(d[axis]) < 1e-12) {
      if (a[axis] < box.min()[axis] || a[axis] > box.max()[axis]) return false;
      continue;
    }
    double ta = (box.min()[axis] - a[axis]) / d[axis], tb = (box.max()[axis] - a[axis]) / d[axis];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

std::vector<WallPart> WallParts(const FloorPlan& floor, double height_m) {
  std::vector<WallPart> parts;
  for (size_t i = 0; i < floor.walls.size(); ++i) {
    const InteriorWall& w = floor.walls[i];
    const int axis = AxisOf(w), across = 1 - axis;
    const double c = w.from_m[across], half = 0.5 * w.thickness_m;
    const double lo = std::min(w.from_m[axis], w.to_m[axis]), hi = std::max(w.from_m[axis], w.to_m[axis]);
    auto box = [&](double a0, double a1, double z0, double z1) {
      Eigen::Vector3d min, max;
      min[axis] = a0;
      max[axis] = a1;
      min[across] = c - half;
      max[across] = c + half;
      min.z() = z0;
      max.z() = z1;
      return Eigen::AlignedBox3d(min, max);
    };
    std::vector<std::pair<double, double>> openings;
    for (const FloorDoor& d : w.doors) {
      const auto [d0, d1] = DoorSpan(w, d);
      openings.emplace_back(std::max(d0, lo), std::min(d1, hi));
      if (d.height_m < height_m)
        parts.push_back({static_cast<int>(i), true, box(std::max(d0, lo), std::min(d1, hi), d.height_m, height_m)});
    }
    std::sort(openings.begin(), openings.end());
    double start = lo;
    for (const auto& [d0, d1] : openings) {
      if (d0 - start > 1e-6) parts.push_back({static_cast<int>(i), false, box(start, d0, 0, height_m)});
      start = std::max(start, d1);
    }
    if (hi - start > 1e-6) parts.push_back({static_cast<int>(i), false, box(start, hi, 0, height_m)});
  }
  return parts;
}

FloorPlan ReadFloorPlan(const json& floor) {
  FloorPlan plan;
  if (floor.is_null()) return plan;
  for (const json& r : floor.at("rooms")) {
    FloorRoom room;
    room.name = r.at("name").get<std::string>();
    room.corridor = r.value("kind", "room") == "corridor";
    room.layout = r.value("layout", "");
    room.box_m = Eigen::AlignedBox2d(Vec2(r.at("min_m")), Vec2(r.at("max_m")));
    plan.rooms.push_back(room);
  }
  for (const json& w : floor.value("walls", json::array())) {
    InteriorWall wall;
    wall.from_m = Vec2(w.at("from_m"));
    wall.to_m = Vec2(w.at("to_m"));
    wall.thickness_m = w.value("thickness_m", 0.12);
    for (const json& d : w.value("doors", json::array())) {
      wall.doors.push_back({d.at("center_m").get<double>(), d.value("width_m", 1.2), d.value("height_m", 2.1)});
    }
    plan.walls.push_back(wall);
  }
  return plan;
}

int RoomAt(const FloorPlan& floor, const Eigen::Vector2d& p) {
  for (size_t i = 0; i < floor.rooms.size(); ++i)
    if (floor.rooms[i].box_m.contains(p)) return static_cast<int>(i);
  return -1;
}

std::vector<std::vector<int>> RoomGraph(const FloorPlan& floor, double height_m) {
  std::vector<std::vector<int>> graph(floor.rooms.size());
  auto join = [&](int a, int b) {
    if (a < 0 || b < 0 || a == b) return;
    if (std::find(graph[a].begin(), graph[a].end(), b) == graph[a].end()) graph[a].push_back(b);
    if (std::find(graph[b].begin(), graph[b].end(), a) == graph[b].end()) graph[b].push_back(a);
  };
  for (const InteriorWall& w : floor.walls) {
    const int axis = AxisOf(w);
    Eigen::Vector2d normal = Eigen::Vector2d::Zero();
    normal[1 - axis] = 1;
    for (const FloorDoor& d : w.doors) {
      const auto [d0, d1] = DoorSpan(w, d);
      Eigen::Vector2d mid = w.from_m;
      mid[axis] = 0.5 * (d0 + d1);
      const double reach = 0.5 * w.thickness_m + 0.05;
      join(RoomAt(floor, mid + reach * normal), RoomAt(floor, mid - reach * normal));
    }
  }
  // Rooms that touch along an edge with no wall at the middle of the shared stretch are open to
  // each other (a corridor running on into a lobby).
  const std::vector<WallPart> parts = WallParts(floor, height_m);
  for (size_t i = 0; i < floor.rooms.size(); ++i) {
    for (size_t j = i + 1; j < floor.rooms.size(); ++j) {
      const Eigen::AlignedBox2d &a = floor.rooms[i].box_m, &b = floor.rooms[j].box_m;
      for (int axis = 0; axis < 2; ++axis) {
        const int other = 1 - axis;
        const bool touch = std::abs(a.max()[axis] - b.min()[axis]) < kToleranceM ||
                           std::abs(b.max()[axis] - a.min()[axis]) < kToleranceM;
        const double lo = std::max(a.min()[other], b.min()[other]), hi = std::min(a.max()[other], b.max()[other]);
        if (!touch || hi - lo < 0.3) continue;
        Eigen::Vector2d mid;
        mid[axis] = std::abs(a.max()[axis] - b.min()[axis]) < kToleranceM ? a.max()[axis] : a.min()[axis];
        mid[other] = 0.5 * (lo + hi);
        const bool walled = std::any_of(parts.begin(), parts.end(), [&](const WallPart& p) {
          return !p.lintel && Eigen::AlignedBox2d(p.box_m.min().head<2>(), p.box_m.max().head<2>()).contains(mid);
        });
        if (!walled) join(static_cast<int>(i), static_cast<int>(j));
      }
    }
  }
  return graph;
}

int WallCrossedBy(const FloorPlan& floor, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double margin_m,
                  double height_m) {
  for (const WallPart& p : WallParts(floor, height_m)) {
    if (p.lintel) continue;
    Eigen::AlignedBox2d box(p.box_m.min().head<2>(), p.box_m.max().head<2>());
    box.min().array() -= margin_m;
    box.max().array() += margin_m;
    if (SegmentMeetsBox(a, b, box)) return p.wall;
  }
  return -1;
}

namespace {

// The room box a floor's rooms and walls must lie in (with the tolerance), and how it reads in messages.
struct RoomBox {
  Eigen::AlignedBox2d outer;
  std::string text;
  explicit RoomBox(const Eigen::Vector3d& size_m)
      : outer(Eigen::Vector2d(-kToleranceM, -kToleranceM), size_m.head<2>().array() + kToleranceM),
        text("x in [0, " + ShortestDouble(size_m.x()) + "], y in [0, " + ShortestDouble(size_m.y()) + "]") {}
};

// The rooms' problems: each at least 0.5 m across, inside the room box, named once, apart from
// the others. False when a room's shape or overlap leaves the room graph meaningless.
bool CheckRooms(const FloorPlan& floor, const RoomBox& box, const std::string& file, ProblemCollector* problems) {
  bool rooms_ok = true;
  for (size_t i = 0; i < floor.rooms.size(); ++i) {
    const FloorRoom& r = floor.rooms[i];
    const std::string at = file + ": /floor/rooms/" + std::to_string(i);
    if ((r.box_m.max() - r.box_m.min()).minCoeff() <= 0.5) {
      problems->Add(at + "/max_m", "a corner at least 0.5 m beyond min_m in x and in y; got min " +
                                       Point(r.box_m.min()) + ", max " + Point(r.box_m.max()));
      rooms_ok = false;
      continue;
    }
    if (!box.outer.contains(r.box_m)) {
      problems->Add(at, "a room inside the room box (" + box.text + "); '" + r.name + "' spans " +
                            Point(r.box_m.min()) + " to " + Point(r.box_m.max()));
    }
    for (size_t j = 0; j < i; ++j) {
      if (floor.rooms[j].name == r.name)
        problems->Add(at + "/name",
                      "a name no other room has; room " + std::to_string(j) + " is also '" + r.name + "'");
      const Eigen::AlignedBox2d overlap = r.box_m.intersection(floor.rooms[j].box_m);
      if (!overlap.isEmpty() && (overlap.max() - overlap.min()).minCoeff() > kToleranceM) {
        problems->Add(at, "a room apart from the others; '" + r.name + "' overlaps room " + std::to_string(j) + " '" +
                              floor.rooms[j].name + "' by " + ShortestDouble(overlap.sizes().x()) + " x " +
                              ShortestDouble(overlap.sizes().y()) + " m");
        rooms_ok = false;
      }
    }
  }
  return rooms_ok;
}

// A wall's doorways' problems (`at`: the wall's place): each within its wall and below the
// ceiling, apart from each other. False when one lies outside its wall.
bool CheckDoors(const InteriorWall& w, double height_m, const std::string& at, ProblemCollector* problems) {
  bool doors_ok = true;
  std::vector<std::pair<double, double>> spans;
  for (size_t k = 0; k < w.doors.size(); ++k) {
    const FloorDoor& door = w.doors[k];
    const std::string door_at = at + "/doors/" + std::to_string(k);
    if (door.center_m - 0.5 * door.width_m < 0 || door.center_m + 0.5 * door.width_m > w.LengthM() + 1e-9) {
      problems->Add(door_at + "/center_m", "a doorway within its wall: the wall is " + ShortestDouble(w.LengthM()) +
                                               " m long, the doorway " + ShortestDouble(door.width_m) +
                                               " m wide centred " + ShortestDouble(door.center_m) + " m along it");
      doors_ok = false;
    }
    if (door.height_m > height_m)
      problems->Add(door_at + "/height_m", "a doorway below the ceiling (" + ShortestDouble(height_m) + " m)");
    spans.push_back(DoorSpan(w, door));
  }
  std::sort(spans.begin(), spans.end());
  for (size_t k = 1; k < spans.size(); ++k) {
    if (spans[k].first < spans[k - 1].second)
      problems->Add(at + "/doors", "doorways apart from each other along the wall");
  }
  return doors_ok;
}

// The walls' problems: each along x or y, inside the room box, with sound doorways. False when a
// wall's shape or a doorway leaves the room graph and the route's check meaningless.
bool CheckWalls(const FloorPlan& floor, const RoomBox& box, double height_m, const std::string& file,
                ProblemCollector* problems) {
  bool walls_ok = true;
  for (size_t i = 0; i < floor.walls.size(); ++i) {
    const InteriorWall& w = floor.walls[i];
    const std::string at = file + ": /floor/walls/" + std::to_string(i);
    const Eigen::Vector2d d = w.to_m - w.from_m;
    if (std::min(std::abs(d.x()), std::abs(d.y())) > 1e-6 || d.norm() < 0.01) {
      problems->Add(at + "/to_m", "a point at least 1 cm from from_m " + Point(w.from_m) +
                                      " with the same x or the same y (walls run along x or y); got " + Point(w.to_m));
      walls_ok = false;
      continue;
    }
    if (!box.outer.contains(w.from_m) || !box.outer.contains(w.to_m))
      problems->Add(at, "a wall inside the room box (" + box.text + ")");
    if (!CheckDoors(w, height_m, at, problems)) walls_ok = false;
  }
  return walls_ok;
}

// Every room reachable from room 0 through doorways and open edges.
void CheckReachable(const FloorPlan& floor, double height_m, const std::string& file, ProblemCollector* problems) {
  const std::vector<std::vector<int>> graph = RoomGraph(floor, height_m);
  std::vector<bool> reached(floor.rooms.size(), false);
  std::deque<int> queue = {0};
  reached[0] = true;
  while (!queue.empty()) {
    const int r = queue.front();
    queue.pop_front();
    for (int n : graph[r])
      if (!reached[n]) reached[n] = true, queue.push_back(n);
  }
  for (size_t i = 0; i < floor.rooms.size(); ++i) {
    if (!reached[i]) {
      problems->Add(file + ": /floor/rooms/" + std::to_string(i), "a room reachable from room 0 '" +
                                                                      floor.rooms[0].name + "' through doorways; '" +
                                                                      floor.rooms[i].name + "' is not");
    }
  }
}

// No leg of the route through an interior wall outside its doorways.
void CheckRouteLegs(const FloorPlan& floor, const std::vector<Eigen::Vector2d>& route, double height_m,
                    const std::string& file, ProblemCollector* problems) {
  for (size_t i = 0; i < route.size(); ++i) {
    const Eigen::Vector2d& a = route[i];
    const Eigen::Vector2d& b = route[(i + 1) % route.size()];
    const int wall = WallCrossedBy(floor, a, b, 0.0, height_m);
    if (wall >= 0) {
      problems->Add(file + ": /route/waypoints_m/" + std::to_string(i),
                    "a leg clear of the interior walls; the leg " + Point(a) + " to " + Point(b) + " (to waypoint " +
                        std::to_string((i + 1) % route.size()) + ") passes through /floor/walls/" +
                        std::to_string(wall) + " outside its doorways");
    }
  }
}

}  // namespace

void CheckFloorPlan(const FloorPlan& floor, const Eigen::Vector3d& size_m, const std::vector<Eigen::Vector2d>& route,
                    const std::string& file, ProblemCollector* problems) {
  if (floor.empty()) return;
  const RoomBox box(size_m);
  const bool rooms_ok = CheckRooms(floor, box, file, problems);
  const bool walls_ok = CheckWalls(floor, box, size_m.z(), file, problems);
  if (rooms_ok && walls_ok) CheckReachable(floor, size_m.z(), file, problems);
  if (walls_ok) CheckRouteLegs(floor, route, size_m.z(), file, problems);
}

}  // namespace hoilcd
