// The scene's crowd as one typed object (the scene's /crowd): who sits where, how people look
// (temperatures, sizes) and move (sway, breathing, postures, activities), seat turnover, walkers
// and people standing still.
#pragma once

#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

#include "hoilcd/core/util/option_table.h"
#include "hoilcd/sim/people/crowd_motion.h"
#include "hoilcd/sim/people/garments.h"

namespace hoilcd {

struct SeatingSpec {
  int table = 0;
  int seat = 0;
  std::string posture;  // "random" or a posture asset name
};

struct StandingSpec {
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  double yaw_deg = 0;
};

// Relative weights of the seated postures.
struct PostureWeights {
  double seated_upright, seated_leaning, seated_arms_on_table, seated_leaning_back;
  double Of(const std::string& posture) const;  // by asset name
};

// Relative weights of the walker behaviours (kWalkerBehaviours).
struct WalkerWeights {
  double ahead, away, approach, stop_to_chat, cross, overtake;
  std::map<std::string, double> ByName() const;
};

struct CrowdOptions {
  int people_per_table;                 // people seated per table when seating is empty
  std::vector<SeatingSpec> seating;     // explicit seats (read by the scene, not the table)
  PostureWeights posture_weights;
  double skin_temperature_c, skin_temperature_sd_c;          // °C, mean and sd between people
  double clothing_temperature_c, clothing_temperature_sd_c;  // °C
  double hair_temperature_c;            // °C
  double height_scale_sd;               // sd of body size between people, fraction
  double breathing_amplitude_m, breathing_period_s;
  double sway_amplitude_deg, sway_period_s;
  double posture_change_interval_s;     // mean time between posture changes, s (0: never)
  ActivityOptions activity;             // activities, their blends, cups and laptops
  double turnover_probability;          // per person and lap boundary
  double heat_print_time_constant_s;    // how fast a left seat cools, s
  int walkers;                          // people walking the robot's route
  WalkerWeights walker_behaviours;
  std::vector<StandingSpec> standing;   // people standing still (read by the scene)
  double bald_fraction;                 // people whose scalp reads as skin
  GarmentOptions garments;              // clothing and skin temperature patterns (garments.h)

  CrowdOptions();  // the registered defaults
  // Every field once: JSON name (the scene's /crowd), unit, default, range, description.
  static const OptionTable<CrowdOptions>& Table();
};

}  // namespace hoilcd
