#include "route_laps.h"

#include <cmath>
#include <string>

namespace hoilcd {

// Frames for `laps` laps of the route: the robot is simulated until it has driven them.
int FramesForLaps(const Scene& scene, const World& world, const std::vector<Eigen::Vector2d>& route, double laps) {
  RouteOptions options = scene.route;
  options.waypoints_m = route;
  double length_m = 0;
  for (size_t i = 0; i < route.size(); ++i) length_m += (route[(i + 1) % route.size()] - route[i]).norm();
  options.frames =
      static_cast<int>(std::ceil(1.5 * laps * length_m / options.cruise_speed_m_s * scene.frame_rate_hz)) + 50;
  const RobotRun run =
      SimulateRobot(scene.robot, options, scene.odometry, world.obstacles(), scene.frame_rate_hz, scene.seed);
  for (const RobotSample& s : run.samples)
    if (s.lap >= laps) return s.frame + 1;
  throw InputError("route", "the robot to complete " + std::to_string(laps) + " laps");
}

}  // namespace hoilcd
