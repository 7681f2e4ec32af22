// What a generated room holds besides its furniture: doors in frames with a light switch beside
// each, a whiteboard on the front wall, an air conditioner high on a wall, sockets near the
// tables, shelves and cabinets on free stretches of wall, ceiling lights in a grid, and what
// people leave by their seats (bags, coats over chair backs, chargers on the table).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "floor_plan.h"
#include "hoilcd/core/util/random.h"
#include "hoilcd/sim/world/world.h"
#include "layouts.h"

namespace hoilcd {

// The room's doorways (scene /room/doors): the middle of each end wall, as a scene without doors
// has, but with a whiteboard on the front wall the west one moves to a corner, or is left out when
// the wall is too narrow for both.
std::vector<Eigen::Vector2d> RoomDoors(const Eigen::Vector2d& size_m, bool whiteboard);

// Whether the family has a front wall for a whiteboard (classroom, seminar_u, meeting_row).
bool HasFrontWall(const std::string& family);

// What a room's fittings and its people's things are placed against, shared by RoomFittings and
// PeoplesThings: the room's furniture `layout`, its doorways (scene /room/doors), the `world` its
// furniture stands in, the robot's `route`, the generator's options, and the stream they draw from.
struct RoomContext {
  const Layout& layout;
  const std::vector<Eigen::Vector2d>& doors;
  const World& world;
  const std::vector<Eigen::Vector2d>& route;
  const GeneratorOptions& options;
  Rng* rng;
};

// The doors' frames and switches, the whiteboard (when `whiteboard`), air conditioner, sockets,
// shelves and cabinets, and the ceiling lights of a room of size_m (x, y, z) with `windows` (scene
// /room/windows); floor-standing cabinets keep route_clearance_m from the route and stay clear of
// every footprint and doorway.
std::vector<PlacedObject> RoomFittings(const Eigen::Vector3d& size_m, const nlohmann::ordered_json& windows,
                                       bool whiteboard, const RoomContext& context);

// Bags beside, coats over and chargers in front of the seats `occupied` (scene /crowd/seating:
// table, seat) in a room of size_m (x, y), each with its option's probability; bags keep clear of
// every footprint in the world and of those placed before them, of every seat's access and of the
// route by route_clearance_m; chargers lie on table tops.
std::vector<PlacedObject> PeoplesThings(const std::vector<std::pair<int, int>>& occupied, const Eigen::Vector2d& size_m,
                                        const RoomContext& context);

}  // namespace hoilcd
