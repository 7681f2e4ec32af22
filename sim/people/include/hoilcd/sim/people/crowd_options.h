// The scene's crowd as one typed object (the scene's /crowd): who sits where, how people look
// (temperatures, sizes) and move (sway, breathing, postures, activities), seat turnover, walkers
// and people standing still.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

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

// Contact heat (docs/models/contact_heat.md): warm prints where people touch chairs, tables,
// laptops and cup handles, cups cooling from their filling and laptops warming after they are
// opened. Each contact warms its footprint toward a steady excess with one time constant and
// cools after release with another.
struct ContactHeatOptions {
  bool enabled;                      // false: chairs, cups and laptops keep their assets' temperatures
  double seat_warm_time_constant_s;  // seat and backrest prints under a sitter, s (excess: furniture.seat_warmth_c)
  double back_excess_k;              // backrest print's steady excess, K
  double table_excess_k, table_warm_time_constant_s, table_cool_time_constant_s;             // forearms on a table top
  double keyboard_excess_k, keyboard_warm_time_constant_s, keyboard_cool_time_constant_s;    // typing hands on a laptop
  double handle_contact_fraction, handle_warm_time_constant_s, handle_cool_time_constant_s;  // a held cup handle
  double cup_fill_c, cup_refill_c, cup_time_constant_s;             // drink poured, refilled when cooled to, Newton τ
  double laptop_warm_time_constant_s, laptop_cool_time_constant_s;  // after opening, after leaving
  double laptop_on_before_max_s;  // laptops in use at the start were opened up to this long before, s

  static const OptionTable<ContactHeatOptions>& Table();
};

struct CrowdOptions {
  int people_per_table;              // people seated per table when seating is empty
  std::vector<SeatingSpec> seating;  // explicit seats (read by the scene, not the table)
  PostureWeights posture_weights;
  double skin_temperature_c, skin_temperature_sd_c;          // °C, mean and sd between people
  double clothing_temperature_c, clothing_temperature_sd_c;  // °C
  double hair_temperature_c;                                 // °C
  double height_scale_sd;                                    // sd of body size between people, fraction
  double breathing_amplitude_m, breathing_period_s;
  double sway_amplitude_deg, sway_period_s;
  double posture_change_interval_s;   // mean time between posture changes, s (0: never)
  ActivityOptions activity;           // activities, their blends, cups and laptops
  double turnover_probability;        // per person and lap boundary
  double heat_print_time_constant_s;  // how fast a left seat cools, s
  ContactHeatOptions contact_heat;    // prints, cups and laptops (docs/models/contact_heat.md)
  int walkers;                        // people walking the robot's route
  WalkerWeights walker_behaviours;
  std::vector<StandingSpec> standing;  // people standing still (read by the scene)
  double bald_fraction;                // people whose scalp reads as skin
  GarmentOptions garments;             // clothing and skin temperature patterns (garments.h)

  CrowdOptions();  // the registered defaults
  // Every field once: JSON name (the scene's /crowd), unit, default, range, description.
  static const OptionTable<CrowdOptions>& Table();
};

}  // namespace hoilcd
