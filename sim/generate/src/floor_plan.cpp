#include "floor_plan.h"

#include <algorithm>
#include <cmath>

namespace hoilcd {

namespace {
bool IsInteriorWall(const Obstacle2D& o) { return o.name.rfind("interior wall ", 0) == 0; }
}  // namespace

bool IsWall(const Obstacle2D& o) {
  return IsInteriorWall(o) || (o.name.size() > 5 && o.name.compare(o.name.size() - 5, 5, " wall") == 0);
}

std::vector<Obstacle2D> InteriorWalls(const World& world) {
  std::vector<Obstacle2D> out;
  for (const Obstacle2D& o : world.obstacles())
    if (IsInteriorWall(o)) out.push_back(o);
  return out;
}

std::vector<Obstacle2D> Furniture(const World& world) {
  std::vector<Obstacle2D> out;
  for (const Obstacle2D& o : world.obstacles())
    if (!IsWall(o)) out.push_back(o);
  return out;
}

std::vector<Eigen::Vector2d> Along(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const int steps = std::max(1, static_cast<int>(std::ceil((b - a).norm() / 0.02)));
  std::vector<Eigen::Vector2d> out;
  for (int i = 0; i <= steps; ++i) out.push_back(a + (b - a) * (static_cast<double>(i) / steps));
  return out;
}

std::vector<Eigen::Vector2d> SeatAccess(const World& world) {
  std::vector<Eigen::Vector2d> out;
  for (const Crowd::SeatPlace& seat : world.seat_places()) {
    const Eigen::Vector2d at = seat.world_from_seat.topRightCorner<2, 1>().cast<double>();
    const Eigen::Vector2d facing = seat.world_from_seat.block<2, 1>(0, 0).cast<double>().normalized();
    out.push_back(seat.chair ? Eigen::Vector2d(at - 0.5 * facing) : Eigen::Vector2d(at + 0.52 * facing));
  }
  return out;
}

}  // namespace hoilcd
