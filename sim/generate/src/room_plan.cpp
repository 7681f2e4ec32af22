#include "room_plan.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace hoilcd {
namespace {

// The route's centre line, every 2 cm.
std::vector<Eigen::Vector2d> RoutePoints(const std::vector<Eigen::Vector2d>& route) {
  std::vector<Eigen::Vector2d> out;
  for (size_t i = 0; i < route.size(); ++i) {
    const std::vector<Eigen::Vector2d> leg = Along(route[i], route[(i + 1) % route.size()]);
    out.insert(out.end(), leg.begin(), leg.end());
  }
  return out;
}

}  // namespace

double WallPlan::Length(Wall wall) const { return wall == kSouth || wall == kNorth ? size_m_.x() : size_m_.y(); }

bool WallPlan::Free(Wall wall, double a, double b, double z0, double z1, double gap_m, double corner_m) const {
  if (a < corner_m || b > Length(wall) - corner_m || z1 > size_m_.z()) return false;
  for (const Span& s : spans_)
    if (s.wall == wall && a < s.b + gap_m && s.a < b + gap_m && z0 < s.z1 && s.z0 < z1) return false;
  return true;
}

std::vector<std::pair<double, double>> WallPlan::FreeStretches(Wall wall, double z0, double z1, double gap_m,
                                                               double corner_m) const {
  std::vector<std::pair<double, double>> taken;
  for (const Span& s : spans_)
    if (s.wall == wall && z0 < s.z1 && s.z0 < z1) taken.emplace_back(s.a - gap_m, s.b + gap_m);
  std::sort(taken.begin(), taken.end());
  std::vector<std::pair<double, double>> out;
  if (z1 > size_m_.z()) return out;
  double from = corner_m;
  for (const auto& [a, b] : taken) {
    if (a > from) out.emplace_back(from, std::min(a, Length(wall) - corner_m));
    from = std::max(from, b);
  }
  if (from < Length(wall) - corner_m) out.emplace_back(from, Length(wall) - corner_m);
  out.erase(std::remove_if(out.begin(), out.end(), [](const auto& s) { return s.second <= s.first; }), out.end());
  return out;
}

PlacedObject WallPlan::On(const std::string& asset, Wall wall, double along_m, double z_m) const {
  switch (wall) {
    case kSouth:
      return {asset, Eigen::Vector3d(along_m, 0, z_m), 90};
    case kNorth:
      return {asset, Eigen::Vector3d(along_m, size_m_.y(), z_m), -90};
    case kWest:
      return {asset, Eigen::Vector3d(0, along_m, z_m), 0};
    case kEast:
      break;
  }
  return {asset, Eigen::Vector3d(size_m_.x(), along_m, z_m), 180};
}

bool Mount(WallPlan* plan, std::vector<PlacedObject>* out, const std::string& asset, Wall wall, double along_m,
           double half_m, double bottom_m, double height_m) {
  if (!plan->Free(wall, along_m - half_m, along_m + half_m, bottom_m, bottom_m + height_m)) return false;
  plan->Take(wall, along_m - half_m, along_m + half_m, bottom_m, bottom_m + height_m);
  out->push_back(plan->On(asset, wall, along_m, bottom_m));
  return true;
}

bool FloorCheck::Clear(const Obstacle2D& o) const {
  const double c = std::cos(o.yaw_rad), s = std::sin(o.yaw_rad);
  const Eigen::Vector2d reach(std::abs(c) * o.half_size_m.x() + std::abs(s) * o.half_size_m.y(),
                              std::abs(s) * o.half_size_m.x() + std::abs(c) * o.half_size_m.y());
  if ((o.center_m - reach).minCoeff() < 0.01 || o.center_m.x() + reach.x() > room_m.x() - 0.01 ||
      o.center_m.y() + reach.y() > room_m.y() - 0.01) {
    return false;
  }
  Obstacle2D grown = o;
  grown.half_size_m += Eigen::Vector2d(0.02, 0.02);
  for (const Obstacle2D& f : footprints)
    if (FootprintsOverlap(grown, f)) return false;
  for (const Eigen::Vector2d& d : doors)
    if (DistanceToObstacle(d, o) < kDoorwayM) return false;
  for (const Eigen::Vector2d& a : access)
    if (DistanceToObstacle(a, o) < kAccessRadiusM + 0.05) return false;
  for (const Eigen::Vector2d& p : route)
    if (DistanceToObstacle(p, o) < clearance_m + 0.01) return false;
  return true;
}

FloorCheck MakeFloorCheck(const Eigen::Vector2d& room_m, const World& world, const std::vector<Eigen::Vector2d>& doors,
                          const std::vector<Eigen::Vector2d>& route, double clearance_m) {
  return {room_m, Furniture(world), doors, SeatAccess(world), RoutePoints(route), clearance_m};
}

Eigen::Vector2d Rotate(double yaw_rad, const Eigen::Vector2d& v) { return Eigen::Rotation2Dd(yaw_rad) * v; }

}  // namespace hoilcd
