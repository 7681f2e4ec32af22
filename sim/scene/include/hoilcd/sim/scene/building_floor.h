// A building floor (the scene's /floor): rooms and corridors inside the room box, divided by
// interior walls with doorways. Gives the walls' solid parts as boxes (the world's mesh and the
// footprints) and checks a floor: rooms apart, walls straight, doorways in their walls, every room
// reachable through doorways, no route leg through a wall (docs/guide/floor.md).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <nlohmann/json_fwd.hpp>

#include "hoilcd/core/util/error.h"

namespace hoilcd {

struct FloorDoor {
  double center_m = 0;    // m, along the wall from its from_m end
  double width_m = 1.2;   // m, clear width
  double height_m = 2.1;  // m, clear height (a lintel above)
};

// A floor-to-ceiling slab along x or y: its centre line from from_m to to_m.
struct InteriorWall {
  Eigen::Vector2d from_m = Eigen::Vector2d::Zero(), to_m = Eigen::Vector2d::Zero();
  double thickness_m = 0.12;  // m
  std::vector<FloorDoor> doors;
  double LengthM() const { return (to_m - from_m).norm(); }
  Eigen::Vector2d Along() const { return (to_m - from_m).normalized(); }  // unit, from from_m to to_m
};

struct FloorRoom {
  std::string name;
  bool corridor = false;  // kind "corridor": passed through, not visited
  std::string layout;     // the generator family its furniture came from ("" when none)
  Eigen::AlignedBox2d box_m;
};

struct FloorPlan {
  std::vector<FloorRoom> rooms;
  std::vector<InteriorWall> walls;
  bool empty() const { return rooms.empty(); }
};

// A solid part of an interior wall (wall index, box): full-height parts between doorways
// (lintel = false) and the lintels above doorways.
struct WallPart {
  int wall = 0;
  bool lintel = false;
  Eigen::AlignedBox3d box_m;
};
std::vector<WallPart> WallParts(const FloorPlan& floor, double height_m);

// The floor plan of the scene's /floor (an empty plan for a null document). The document has
// passed the schema.
FloorPlan ReadFloorPlan(const nlohmann::json& floor);

// The room whose rectangle holds p (-1: none).
int RoomAt(const FloorPlan& floor, const Eigen::Vector2d& p);

// Which rooms are joined to which: through a doorway (the rooms on its two sides) or along a
// shared edge no wall stands on. adjacency[i] lists room i's neighbours.
std::vector<std::vector<int>> RoomGraph(const FloorPlan& floor, double height_m);

// Whether the segment a-b meets the box (Liang-Barsky clipping).
bool SegmentMeetsBox(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::AlignedBox2d& box);

// The wall whose full-height part the segment a-b comes within margin_m of (-1: none).
int WallCrossedBy(const FloorPlan& floor, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double margin_m,
                  double height_m);

// Every problem of the floor within a room box of size_m, each at its JSON pointer under `file`:
// rooms inside the box and apart, walls along x or y inside the box, doorways within their walls
// and below the ceiling, every room reachable from the first through doorways, no route leg
// through a wall.
void CheckFloorPlan(const FloorPlan& floor, const Eigen::Vector3d& size_m, const std::vector<Eigen::Vector2d>& route,
                    const std::string& file, ProblemCollector* problems);

}  // namespace hoilcd
