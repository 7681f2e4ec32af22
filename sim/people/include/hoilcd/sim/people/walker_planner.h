// Where walkers go: the robot's run as they see it, the room's free space for a body (obstacle
// footprints grown by the body radius, with a visibility graph over their corners searched by
// Dijkstra for the shortest collision-free path), and each walker's plan of behaviour bouts, each
// walked into from a door and out through one, made against the walkers planned before it
// (priority planning: no two footprints ever meet).
#pragma once

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "hoilcd/core/util/random.h"
#include "hoilcd/sim/robot/robot.h"

namespace hoilcd {

// Walkers' footprint: a circle of this radius (times the body scale) about the pelvis; the
// shoulders are 0.48 m wide at scale 1.
constexpr double kWalkerRadiusM = 0.25;
// Closest a walker's centre comes to the robot's base origin (footprint 0.42 × 0.34 m), m.
constexpr double kWalkerRobotClearanceM = 0.6;
// Route-following walkers stay at least this much route time ahead of the robot, s.
constexpr double kMinWalkerLeadS = 3.0;
// A walker keeping pace ahead of the robot starts at least this much route time ahead (about 2 m
// from the camera at the robot's 0.45 m/s: beyond Hall's 1.2 m personal distance), s.
constexpr double kMinAheadLeadS = 4.0;

// What walkers do, in the order of crowd.walker_behaviours in the scene schema: "ahead" keeps
// pace (the original pattern), "away" walks off faster than the robot, "approach" comes towards
// it (facing it) and turns back, "stop_to_chat" stands facing the tables, "cross" walks across
// the robot's path in front of it on a free path, "overtake" comes from behind and passes it
// beside its route. Between bouts a walker walks in through a door ("enter") and out through one
// ("leave") on free paths; "gone" (out of the room) fills the gaps.
constexpr size_t kWalkerBehaviourCount = 6;
extern const std::array<const char*, kWalkerBehaviourCount> kWalkerBehaviours;

// The robot's run, one sample per frame.
class RobotTrack {
 public:
  RobotTrack() = default;
  explicit RobotTrack(const std::vector<RobotSample>& samples);
  bool empty() const { return samples_.empty(); }
  double start_s() const { return samples_.front().time_s; }
  double end_s() const { return samples_.back().time_s; }
  // Base position and heading (rad) at time t, interpolated, clamped to the run.
  Eigen::Vector2d At(double time_s, double* heading_rad = nullptr) const;
  // Distance the base has driven up to time t, m.
  double DistanceAt(double time_s) const;
  // The median speed while moving, m/s (0.45 if it never moves).
  double cruise_speed_m_s() const { return cruise_speed_m_s_; }

 private:
  struct Sample {
    double time_s, x_m, y_m, theta_rad, distance_m;
  };
  size_t After(double time_s) const;
  std::vector<Sample> samples_;
  double cruise_speed_m_s_ = 0.45;
};

// The floor a body of a given radius can stand on.
class FreeSpace {
 public:
  FreeSpace(std::vector<Obstacle2D> obstacles, double radius_m);
  double radius_m() const { return radius_m_; }
  // Distance from the body's edge at p to the nearest footprint, m (< 0: they overlap);
  // nearest receives that footprint's name.
  double Clearance(const Eigen::Vector2d& p, std::string* nearest = nullptr) const;
  bool SegmentFree(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;
  // p, or the free point nearest to it along ±direction within max_shift_m (5 mm steps);
  // nullopt when there is none.
  std::optional<Eigen::Vector2d> FreeAlong(const Eigen::Vector2d& p, const Eigen::Vector2d& direction,
                                           double max_shift_m) const;
  // The shortest free polyline from a to b (both ends included), or empty when none exists.
  std::vector<Eigen::Vector2d> ShortestPath(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;

 private:
  std::vector<Obstacle2D> obstacles_;
  double radius_m_;
  std::vector<Eigen::Vector2d> nodes_;                      // free corners of the grown footprints
  std::vector<std::vector<std::pair<int, double>>> edges_;  // visible neighbours, length m
};

// A doorway as walkers use it: its centre on the wall, the wall's normal into the room, its width.
struct Doorway {
  Eigen::Vector2d center_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d inward = Eigen::Vector2d::UnitX();
  double width_m = 0.9;
};
// Where a body of this radius stands in the doorway just inside the room, clear of the wall.
Eigen::Vector2d DoorThreshold(const Doorway& door, double radius_m);

struct WalkerSegment {
  std::string behaviour;                // one of kWalkerBehaviours, "enter", "leave" or "gone"
  double start_s = 0, end_s = 0;        // time
  double u_start = 0, rate = 1;         // on the route: route time u(t) = u_start + rate (t - start_s),
                                        // the place the robot passes at time u
  std::vector<Eigen::Vector2d> path_m;  // "cross", "enter", "leave": walked from start_s at speed_m_s
                                        // (not on the route; a door walk starts or ends outside)
  double speed_m_s = 0;
  double pass_offset_m = 0;  // "overtake": to the left of the route (< 0: right) while passing
};

// A route-following walker steps up to this far aside where the robot's path passes closer to
// furniture than the walker's radius, m.
constexpr double kWalkerMaxSidestepM = 0.15;

struct WalkerPlan {
  std::vector<WalkerSegment> segments;     // back to back from time 0
  double radius_m = kWalkerRadiusM;        // footprint
  std::shared_ptr<const FreeSpace> space;  // where its body fits (null: anywhere)
  double lateral_m = 0;                    // on the route: this far to its left, m
  // The segment at time t (the last one beyond the end).
  const WalkerSegment& At(double time_s) const;
  double RouteTime(double time_s) const;
  // Path length walked up to time t, in route seconds (|rate| integrated; paths at their speed).
  double Walked(double time_s) const;
};

// Where a walker is: floor position, facing (rad), walking speed (m/s); a route-following walker
// keeps the plan's lateral_m to the left of the route (and steps aside from furniture).
struct WalkerPlacement {
  Eigen::Vector2d at_m = Eigen::Vector2d::Zero();
  double heading_rad = 0, speed_m_s = 0;
  bool present = false;  // in the room or in a doorway (not "gone")
};
WalkerPlacement PlaceWalker(const WalkerPlan& plan, const RobotTrack& robot, double time_s);

// Plans one walker over [0, duration_s] by the behaviour weights (keyed by seed and walker), in
// free space (its radius is the plan's), clear of the robot and of the walkers planned before it.
// It starts the run in the room; later bouts begin with a walk in through one of the doors and
// every stay ends with a walk out through one, so it appears and vanishes only behind a doorway.
// A bout that the room leaves no space for here and now (no free way in or out, a clash) is drawn
// again among the others.
WalkerPlan PlanWalker(const std::map<std::string, double>& weights, uint64_t seed, int walker, double duration_s,
                      std::shared_ptr<const FreeSpace> space, const RobotTrack& robot,
                      const std::vector<WalkerPlan>& others, const std::vector<Doorway>& doors, double lateral_m);

}  // namespace hoilcd
