// The floor of a generated room as its checks see it: the footprints that stand on it (every one
// but the walls), points along a line, and where a person stands before sitting on each seat.
// Shared by the scene checks (generator.cpp) and the room objects' placement (room_objects.cpp).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "hoilcd/sim/world/world.h"

namespace hoilcd {

constexpr double kAccessRadiusM = 0.18;  // a person squeezing to their seat, m

// Whether a footprint is one of the room's walls (outer or, on a building floor, interior).
bool IsWall(const Obstacle2D& o);

// The footprints of a building floor's interior walls (none in a single room).
std::vector<Obstacle2D> InteriorWalls(const World& world);

// The furniture, objects and standing people: every footprint but the walls.
std::vector<Obstacle2D> Furniture(const World& world);

// Points every 2 cm from a to b, both ends included.
std::vector<Eigen::Vector2d> Along(const Eigen::Vector2d& a, const Eigen::Vector2d& b);

// Where a person stands before sitting, one per world.seat_places() in its order: behind a chair,
// in front of a sofa place.
std::vector<Eigen::Vector2d> SeatAccess(const World& world);

}  // namespace hoilcd
