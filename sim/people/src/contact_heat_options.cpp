// The scene's /crowd/contact_heat: every figure of the contact heat model with its default, unit
// and range; docs/models/contact_heat.md gives each figure's source.
#include "hoilcd/sim/people/crowd_options.h"

namespace hoilcd {

const OptionTable<ContactHeatOptions>& ContactHeatOptions::Table() {
  using O = ContactHeatOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("enabled", &O::enabled, true,
               "warm prints where people touch chairs, tables, laptops and cup handles; cups cool, laptops warm up "
               "(false: they keep their assets' temperatures)")
          .Add("seat_warm_time_constant_s", &O::seat_warm_time_constant_s, 120.0, "s", R::Closed(1, 36000),
               "a seat's and backrest's print warms toward its steady excess (furniture.seat_warmth_c) with this time "
               "constant")
          .Add("back_excess_k", &O::back_excess_k, 1.5, "K", R::Closed(0, 20),
               "steady excess of a backrest's print where a back leans on it")
          .Add("table_excess_k", &O::table_excess_k, 3.0, "K", R::Closed(0, 20),
               "steady excess of a table top under a resting forearm and hand")
          .Add("table_warm_time_constant_s", &O::table_warm_time_constant_s, 30.0, "s", R::Closed(1, 36000),
               "a table print warms with this time constant")
          .Add("table_cool_time_constant_s", &O::table_cool_time_constant_s, 45.0, "s", R::Closed(1, 36000),
               "a table print cools with this time constant once the arm is lifted")
          .Add("keyboard_excess_k", &O::keyboard_excess_k, 2.0, "K", R::Closed(0, 20),
               "steady excess of a laptop's palm rest and keys under typing hands")
          .Add("keyboard_warm_time_constant_s", &O::keyboard_warm_time_constant_s, 10.0, "s", R::Closed(1, 36000),
               "a keyboard print warms with this time constant")
          .Add("keyboard_cool_time_constant_s", &O::keyboard_cool_time_constant_s, 30.0, "s", R::Closed(1, 36000),
               "a keyboard print cools with this time constant once typing stops")
          .Add("handle_contact_fraction", &O::handle_contact_fraction, 0.3, "", R::Closed(0, 1),
               "a held cup handle moves this fraction of the way from the mug's temperature to the skin's")
          .Add("handle_warm_time_constant_s", &O::handle_warm_time_constant_s, 5.0, "s", R::Closed(1, 36000),
               "a handle print forms with this time constant")
          .Add("handle_cool_time_constant_s", &O::handle_cool_time_constant_s, 20.0, "s", R::Closed(1, 36000),
               "a handle print fades with this time constant once the cup is put down")
          .Add("cup_fill_c", &O::cup_fill_c, 75.0, "°C", R::Closed(30, 100),
               "a drink's temperature when poured (a newcomer's cup is fresh)")
          .Add("cup_refill_c", &O::cup_refill_c, 40.0, "°C", R::Closed(0, 100),
               "a drink cooled to this is refilled to cup_fill_c (cups at the start are at a random point of that "
               "cycle)")
          .Add("cup_time_constant_s", &O::cup_time_constant_s, 1700.0, "s", R::Closed(1, 36000),
               "Newton's-law time constant of a filled ceramic mug cooling toward the room")
          .Add("laptop_warm_time_constant_s", &O::laptop_warm_time_constant_s, 600.0, "s", R::Closed(1, 36000),
               "an opened laptop warms toward its asset's temperatures with this time constant")
          .Add("laptop_cool_time_constant_s", &O::laptop_cool_time_constant_s, 900.0, "s", R::Closed(1, 36000),
               "a laptop cools toward the room with this time constant after its user leaves")
          .Add("laptop_on_before_max_s", &O::laptop_on_before_max_s, 3600.0, "s", R::Closed(0, 86400),
               "laptops of people seated at the start were opened a random time up to this long before it")
          .Rule("cup_refill_c", [](const O& o) { return o.cup_refill_c < o.cup_fill_c ? "" : "below cup_fill_c"; });
  return table;
}

}  // namespace hoilcd
