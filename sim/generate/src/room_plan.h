// What a generated room's walls and floor already hold, for placing more: the stretches of each
// wall taken (WallPlan) and the floor a floor object may stand on (FloorCheck). Shared by the
// fittings and people's things (room_objects.cpp) and the clutter (clutter.cpp).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "floor_plan.h"
#include "layouts.h"

namespace hoilcd {

constexpr double kCornerM = 0.1;   // fittings keep this far from a room corner
constexpr double kGapM = 0.1;      // and from each other along a wall
constexpr double kDoorwayM = 1.0;  // floor objects keep this far from a doorway's centre

enum Wall { kSouth, kNorth, kWest, kEast };

// A stretch of wall taken: along the wall (x for south and north, y for west and east) and in
// height.
struct Span {
  Wall wall;
  double a, b, z0, z1;
};

class WallPlan {
 public:
  explicit WallPlan(const Eigen::Vector3d& size_m) : size_m_(size_m) {}

  double Length(Wall wall) const;

  // Whether [a, b] × [z0, z1] on `wall` is under the ceiling, corner_m from the corners and gap_m
  // along the wall from every stretch taken that it shares heights with.
  bool Free(Wall wall, double a, double b, double z0, double z1, double gap_m = kGapM,
            double corner_m = kCornerM) const;

  // The free stretches of `wall` over heights [z0, z1], in order along it (same rules as Free).
  std::vector<std::pair<double, double>> FreeStretches(Wall wall, double z0, double z1, double gap_m,
                                                       double corner_m) const;

  void Take(Wall wall, double a, double b, double z0, double z1) { spans_.push_back({wall, a, b, z0, z1}); }

  // An object with its back on `wall` at `along_m`, its bottom at z_m: the asset's origin and yaw.
  PlacedObject On(const std::string& asset, Wall wall, double along_m, double z_m) const;

 private:
  Eigen::Vector3d size_m_;
  std::vector<Span> spans_;
};

// Takes the stretch and places the object when the stretch is free.
bool Mount(WallPlan* plan, std::vector<PlacedObject>* out, const std::string& asset, Wall wall, double along_m,
           double half_m, double bottom_m, double height_m);

// A floor object's footprint clear of the walls, every other footprint, the doorways, the seats'
// access and the route.
struct FloorCheck {
  Eigen::Vector2d room_m;
  std::vector<Obstacle2D> footprints;
  std::vector<Eigen::Vector2d> doors, access, route;
  double clearance_m;

  bool Clear(const Obstacle2D& o) const;
};

// The check for a room of room_m (x, y) furnished as `world`, its doors and the robot's route.
FloorCheck MakeFloorCheck(const Eigen::Vector2d& room_m, const World& world, const std::vector<Eigen::Vector2d>& doors,
                          const std::vector<Eigen::Vector2d>& route, double clearance_m);

Eigen::Vector2d Rotate(double yaw_rad, const Eigen::Vector2d& v);

}  // namespace hoilcd
