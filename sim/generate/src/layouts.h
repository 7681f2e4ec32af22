// The furniture rules of each layout family: what stands where in a room of a drawn size, how
// each piece seats people, and the rectangle the robot's route runs round.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "hoilcd/core/util/random.h"
#include "hoilcd/sim/generate/generator.h"

namespace hoilcd {

// One element of the scene's /tables (asset "" and seats "both_sides" are left out of the file).
struct Piece {
  std::string asset;
  Eigen::Vector2d center_m = Eigen::Vector2d::Zero();
  double yaw_deg = 0;
  std::string seats = "both_sides";
  int seat_count = 0;
};

// One element of /objects (monitors on desks, partitions, a lectern).
struct PlacedObject {
  std::string asset;
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  double yaw_deg = 0;
};

// One element of /crowd/standing.
struct StandingPerson {
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  double yaw_deg = 0;
};

struct Layout {
  std::vector<Piece> pieces;
  std::vector<PlacedObject> objects;
  std::vector<StandingPerson> standing;
  Eigen::Vector4d route_box_m = Eigen::Vector4d::Zero();  // x0, y0, x1, y1: the route's corners
  double cup_fraction = 0.5, laptop_fraction = 0.2;       // the family's props (crowd)
};

// The furniture of `family` in a room of size_m (x, y), drawn from rng; every footprint keeps
// options.route_clearance_m from the route box's edges and stays inside the room.
Layout DrawLayout(const std::string& family, const Eigen::Vector2d& size_m, const GeneratorOptions& options, Rng* rng);

}  // namespace hoilcd
