#include "hoilcd/sim/people/crowd_options.h"

#include "hoilcd/core/util/error.h"

namespace hoilcd {

double PostureWeights::Of(const std::string& posture) const {
  if (posture == "seated_upright") return seated_upright;
  if (posture == "seated_leaning") return seated_leaning;
  if (posture == "seated_arms_on_table") return seated_arms_on_table;
  HOILCD_CHECK_MSG(posture == "seated_leaning_back", posture);
  return seated_leaning_back;
}

std::map<std::string, double> WalkerWeights::ByName() const {
  return {{"ahead", ahead}, {"away", away},        {"approach", approach}, {"stop_to_chat", stop_to_chat},
          {"cross", cross}, {"overtake", overtake}};
}

CrowdOptions::CrowdOptions() { Table().FillDefaults(this); }

const OptionTable<CrowdOptions>& CrowdOptions::Table() {
  using O = CrowdOptions;
  using R = OptionRange;
  using P = PostureWeights;
  using W = WalkerWeights;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("people_per_table", &O::people_per_table, 4, "", R::Closed(0, 6),
               "people seated per table when seating is empty")
          .External("seating",
                    "explicit seats: [{table, seat, posture}]; empty: people_per_table random seats per table")
          .Nest("posture_weights", &O::posture_weights,
                OptionTable<P>()
                    .Add("seated_upright", &P::seated_upright, 1.0, "", R().AtLeast(0), "relative weight")
                    .Add("seated_leaning", &P::seated_leaning, 1.0, "", R().AtLeast(0), "relative weight")
                    .Add("seated_arms_on_table", &P::seated_arms_on_table, 1.0, "", R().AtLeast(0), "relative weight")
                    .Add("seated_leaning_back", &P::seated_leaning_back, 0.5, "", R().AtLeast(0), "relative weight"))
          .Add("skin_temperature_c", &O::skin_temperature_c, 34.0, "°C", R::Closed(-50, 200), "mean skin temperature")
          .Add("skin_temperature_sd_c", &O::skin_temperature_sd_c, 0.5, "°C", R::Closed(0, 5),
               "skin temperature sd between people")
          .Add("clothing_temperature_c", &O::clothing_temperature_c, 28.5, "°C", R::Closed(-50, 200),
               "mean upper clothing temperature (only with garments.enabled false)")
          .Add("clothing_temperature_sd_c", &O::clothing_temperature_sd_c, 0.5, "°C", R::Closed(0, 5),
               "clothing temperature sd between people")
          .Add("hair_temperature_c", &O::hair_temperature_c, 30.0, "°C", R::Closed(-50, 200), "mean hair temperature")
          .Add("height_scale_sd", &O::height_scale_sd, 0.04, "", R::Closed(0, 0.3),
               "sd of body size between people, fraction")
          .Add("breathing_amplitude_m", &O::breathing_amplitude_m, 0.004, "m", R::Closed(0, 0.05),
               "chest rise when breathing")
          .Add("breathing_period_s", &O::breathing_period_s, 4.0, "s", R().Above(0), "breathing period")
          .Add("sway_amplitude_deg", &O::sway_amplitude_deg, 3.0, "deg", R::Closed(0, 30),
               "idle sway of the upper body")
          .Add("sway_period_s", &O::sway_period_s, 7.0, "s", R().Above(0), "mean sway period")
          .Add("posture_change_interval_s", &O::posture_change_interval_s, 30.0, "s", R().AtLeast(0),
               "mean time between posture changes (0: never)")
          // Interval 0 is "never"; a tiny one would make a posture change per nanosecond.
          .Rule("posture_change_interval_s",
                [](const O& o) {
                  return o.posture_change_interval_s == 0 || o.posture_change_interval_s >= 1
                             ? ""
                             : "0 (never) or at least 1 s";
                })
          .Flatten(&O::activity, ActivityOptions::Table())
          .Add("turnover_probability", &O::turnover_probability, 0.0, "", R::Closed(0, 1),
               "chance per person and lap boundary of leaving (half of it: changing seats)")
          .Add("heat_print_time_constant_s", &O::heat_print_time_constant_s, 120.0, "s", R().AtLeast(0.001),
               "how fast a seat's print cools after its person leaves (docs/models/contact_heat.md)")
          .Nest("contact_heat", &O::contact_heat, ContactHeatOptions::Table())
          .Add("walkers", &O::walkers, 0, "", R::Closed(0, 8), "people walking the robot's route ahead of it")
          .Nest("walker_behaviours", &O::walker_behaviours,
                OptionTable<W>()
                    .Add("ahead", &W::ahead, 1.0, "", R::Closed(0, 1000), "relative weight: keeps pace ahead")
                    .Add("away", &W::away, 0.3, "", R::Closed(0, 1000), "relative weight: walks off faster")
                    .Add("approach", &W::approach, 0.3, "", R::Closed(0, 1000),
                         "relative weight: comes towards the robot")
                    .Add("stop_to_chat", &W::stop_to_chat, 0.3, "", R::Closed(0, 1000),
                         "relative weight: stands facing the tables")
                    .Add("cross", &W::cross, 0.0, "", R::Closed(0, 1000), "relative weight: crosses the robot's path")
                    .Add("overtake", &W::overtake, 0.0, "", R::Closed(0, 1000),
                         "relative weight: passes the robot from behind"))
          .External("standing", "people standing still: [{position_m, yaw_deg}]")
          .Add("bald_fraction", &O::bald_fraction, 0.15, "", R::Closed(0, 1), "people whose scalp reads as skin")
          .Nest("garments", &O::garments, GarmentOptions::Table());
  return table;
}

}  // namespace hoilcd
