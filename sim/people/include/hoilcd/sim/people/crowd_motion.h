// How seated people move between posture changes: a seeded stochastic process per person (keyed
// by seed, person and time, never by thread) choosing among idle sway, head turns (towards a
// neighbour or the robot), talking gestures, drinking from the cup in front of them and typing at
// their laptop, with smooth ramps in and out; and the overlay of an activity on a body pose.
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "hoilcd/core/util/option_table.h"
#include "hoilcd/sim/assets/skeleton.h"

namespace hoilcd {

// The activities, in the order of crowd.activities in the scene schema.
extern const std::array<const char*, 5> kActivityNames;

struct ActivitySpec {
  double weight = 1;   // relative frequency when a new activity is chosen, ≥ 0
  double dwell_s = 5;  // mean duration (exponential, at least 1.5 s), s
};

struct ActivityOptions {
  std::map<std::string, ActivitySpec> activities;  // by kActivityNames
  double blend_s;                                  // ramp into and out of an activity, s
  double posture_blend_s;                          // a posture change takes this long, s
  double cup_fraction;                             // seated people with a cup in front of them, 0-1
  double laptop_fraction;                          // seated people with a laptop in front of them, 0-1

  ActivityOptions();  // the registered defaults
  // Every field once: JSON name (in the scene's /crowd), unit, default, range, description.
  static const OptionTable<ActivityOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

struct ActivityEpisode {
  std::string name;  // one of kActivityNames
  double start_s = 0, end_s = 0;
  bool toward_robot = false;     // head turns: look at the robot, else at a neighbour
  double neighbour_pick = 0;     // which neighbour (at the table when the episode starts), 0-1
  double lone_gaze_yaw_rad = 0;  // with nobody else at the table: a glance this way, seat frame
  double gaze_yaw_rad = 0;       // where they look (seat frame, counter-clockwise from +x; talking,
                                 // head turns): set by the Crowd from the neighbours present
  int side = 1;                  // gesturing / drinking hand: 0 left, 1 right
  double phase_rad = 0;          // phase of the gesture oscillations
};

// The episodes of one person from from_s to to_s (back to back; "idle" fills the gaps). Who
// they look at is drawn as neighbour_pick; GazeAt turns it into a direction once the table's
// people are known.
std::vector<ActivityEpisode> PlanActivities(const ActivityOptions& options, uint64_t seed, int person_id, double from_s,
                                            double to_s, bool has_cup, bool has_laptop);

// Sets episode.gaze_yaw_rad: towards the neighbour neighbour_pick selects among
// neighbour_yaw_rad (directions, seat frame, of the people at the table when it starts), or
// lone_gaze_yaw_rad when there is nobody.
void GazeAt(const std::vector<double>& neighbour_yaw_rad, ActivityEpisode* episode);

// Props a person handles, seat frame.
struct Props {
  Eigen::Vector3d cup_at_m = Eigen::Vector3d::Zero();     // cup's resting place (base centre)
  Eigen::Vector3d laptop_at_m = Eigen::Vector3d::Zero();  // laptop's base centre
};

// The base pose with the episode's motion overlaid at time t (seat frame). robot_yaw_rad: where
// the robot is, seen from the seat. seat_from_cup receives the cup's pose (resting or in hand).
BodyPose ApplyActivity(const Skeleton& skeleton, const BodyPose& base, const ActivityEpisode& episode, double time_s,
                       double blend_s, const Props& props, double robot_yaw_rad, Eigen::Matrix4d* seat_from_cup);

}  // namespace hoilcd
