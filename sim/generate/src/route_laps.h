// How many frames a scene's robot needs to drive a number of laps of a route (shared by the
// room generator and the building floor's).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "hoilcd/sim/scene/scene.h"
#include "hoilcd/sim/world/world.h"

namespace hoilcd {

// Frames for `laps` laps of the route: the robot is simulated until it has driven them.
int FramesForLaps(const Scene& scene, const World& world, const std::vector<Eigen::Vector2d>& route, double laps);

}  // namespace hoilcd
