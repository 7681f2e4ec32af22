#include "hoilcd/core/util/error.h"
#include "hoilcd/sim/generate/generator.h"

namespace hoilcd {
namespace {

// A family's size table: its defaults, and the smallest room its rules can furnish.
OptionTable<RoomSizeRange> SizeTable(RoomSizeRange defaults, double smallest_length_m, double smallest_width_m) {
  using O = RoomSizeRange;
  using R = OptionRange;
  return OptionTable<O>()
      .Add("length_min_m", &O::length_min_m, defaults.length_min_m, "m", R::Closed(smallest_length_m, 30),
           "shortest room (along x, uniform)")
      .Add("length_max_m", &O::length_max_m, defaults.length_max_m, "m", R::Closed(smallest_length_m, 30),
           "longest room (along x, uniform)")
      .Add("width_min_m", &O::width_min_m, defaults.width_min_m, "m", R::Closed(smallest_width_m, 20),
           "narrowest room (along y, uniform)")
      .Add("width_max_m", &O::width_max_m, defaults.width_max_m, "m", R::Closed(smallest_width_m, 20),
           "widest room (along y, uniform)")
      .Rule("length_max_m", [](const O& o) { return o.length_max_m >= o.length_min_m ? "" : "at least length_min_m"; })
      .Rule("width_max_m", [](const O& o) { return o.width_max_m >= o.width_min_m ? "" : "at least width_min_m"; });
}

}  // namespace

const OptionTable<RoomObjectOptions>& RoomObjectOptions::Table() {
  using O = RoomObjectOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("whiteboard_probability", &O::whiteboard_probability, 0.9, "", R::Closed(0, 1),
               "chance of a whiteboard on the front (west) wall of a classroom, seminar_u or meeting_row room")
          .Add("ac_unit_probability", &O::ac_unit_probability, 0.6, "", R::Closed(0, 1),
               "chance of a split air conditioner high on the south or east wall")
          .Add("socket_probability", &O::socket_probability, 0.5, "", R::Closed(0, 1),
               "chance of a wall socket on the nearer long wall, per table or desk")
          .Add("shelf_count_max", &O::shelf_count_max, 2, "", R::Closed(0, 6), "most wall shelves (uniform in 0..this)")
          .Add("cabinet_count_max", &O::cabinet_count_max, 2, "", R::Closed(0, 6),
               "most floor cabinets against free wall (uniform in 0..this)")
          .Add("ceiling_light_spacing_m", &O::ceiling_light_spacing_m, 2.4, "m", R::Closed(1.2, 6),
               "pitch of the grid of ceiling lights")
          .Add("bag_probability", &O::bag_probability, 0.3, "", R::Closed(0, 1),
               "chance of a bag on the floor beside an occupied chair")
          .Add("coat_probability", &O::coat_probability, 0.25, "", R::Closed(0, 1),
               "chance of a coat over an occupied chair's backrest")
          .Add("charger_probability", &O::charger_probability, 0.2, "", R::Closed(0, 1),
               "chance of a charger on the table top beside an occupied seat")
          .Add("clutter_density", &O::clutter_density, 1.0, "", R::Closed(0, 2),
               "the clutter of lived-in rooms (things on tables, walls, floors, ceilings and shelves): 0 none, 1 "
               "typical, "
               "2 twice that");
  return table;
}

const std::vector<std::string>& LayoutFamilies() {
  static const std::vector<std::string> families = {"meeting_row", "classroom", "cafeteria",
                                                    "open_office", "seminar_u", "lounge"};
  return families;
}

GeneratorOptions::GeneratorOptions() { Table().FillDefaults(this); }

const RoomSizeRange& GeneratorOptions::SizeOf(const std::string& family) const {
  if (family == "meeting_row") return meeting_row;
  if (family == "classroom") return classroom;
  if (family == "cafeteria") return cafeteria;
  if (family == "open_office") return open_office;
  if (family == "seminar_u") return seminar_u;
  HOILCD_CHECK_MSG(family == "lounge", family);
  return lounge;
}

const OptionTable<GeneratorOptions>& GeneratorOptions::Table() {
  using O = GeneratorOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Nest("meeting_row", &O::meeting_row, SizeTable({4.0, 12.0, 3.2, 5.0}, 3.5, 3.2))
          .Nest("classroom", &O::classroom, SizeTable({6.0, 12.0, 4.5, 8.0}, 5.0, 3.5))
          .Nest("cafeteria", &O::cafeteria, SizeTable({6.0, 15.0, 4.0, 8.0}, 3.6, 3.6))
          .Nest("open_office", &O::open_office, SizeTable({6.0, 15.0, 5.6, 8.0}, 4.0, 4.0))
          .Nest("seminar_u", &O::seminar_u, SizeTable({6.0, 10.0, 5.0, 7.0}, 5.0, 4.2))
          .Nest("lounge", &O::lounge, SizeTable({5.0, 10.0, 3.4, 7.0}, 4.0, 3.4))
          .Add("height_min_m", &O::height_min_m, 2.5, "m", R::Closed(2.2, 6), "lowest ceiling (uniform)")
          .Add("height_max_m", &O::height_max_m, 3.2, "m", R::Closed(2.2, 6), "highest ceiling (uniform)")
          .Rule("height_max_m",
                [](const O& o) { return o.height_max_m >= o.height_min_m ? "" : "at least height_min_m"; })
          .Add("occupancy_min", &O::occupancy_min, 0.4, "", R::Closed(0, 1),
               "fewest seats taken, a fraction (uniform per room)")
          .Add("occupancy_max", &O::occupancy_max, 1.0, "", R::Closed(0, 1),
               "most seats taken, a fraction (uniform per room)")
          .Rule("occupancy_max",
                [](const O& o) { return o.occupancy_max >= o.occupancy_min ? "" : "at least occupancy_min"; })
          .Add("posture_weight_min", &O::posture_weight_min, 0.25, "", R::Closed(0, 100),
               "smallest weight of each seated posture (uniform per room)")
          .Add("posture_weight_max", &O::posture_weight_max, 1.5, "", R::Closed(0, 100),
               "largest weight of each seated posture (uniform per room)")
          .Rule("posture_weight_max",
                [](const O& o) {
                  return o.posture_weight_max >= o.posture_weight_min && o.posture_weight_max > 0
                             ? ""
                             : "above 0 and at least posture_weight_min";
                })
          .Add("activity_weight_spread", &O::activity_weight_spread, 0.5, "", R::Closed(0, 1),
               "each activity's weight is its default times a factor uniform in [1 - this, 1 + this] per room")
          .Add("walkers_max", &O::walkers_max, 2, "", R::Closed(0, 8), "most walkers in a room (uniform in 0..this)")
          .Add("turnover_max", &O::turnover_max, 0.2, "", R::Closed(0, 1),
               "largest crowd.turnover_probability (uniform in [0, this] per room)")
          .Add("glossy_floor_probability", &O::glossy_floor_probability, 0.5, "", R::Closed(0, 1),
               "chance of a glossy floor (epoxy, polished vinyl, polished concrete or lacquered wood, equally likely; "
               "docs/models/sensor_and_thermal.md), else a matte one (carpet, matte finish)")
          .Add("laps", &O::laps, 2.0, "", R::Closed(1, 10), "laps the robot drives; the scene's frames end when it has")
          .Add("route_wall_m", &O::route_wall_m, 0.4, "m", R::Closed(0.3, 1.5), "route from the walls")
          .Add("route_clearance_m", &O::route_clearance_m, 0.4, "m", R::Closed(0.3, 1.5),
               "least distance from the route's centre line to any footprint (the robot is 0.34 m wide)")
          .Add("attempts", &O::attempts, 20, "", R::Closed(1, 1000), "draws of a scene before it is given up")
          .Nest("objects", &O::objects, RoomObjectOptions::Table())
          .Nest("floor", &O::floor, FloorLayoutOptions::Table());
  return table;
}

const OptionTable<FloorLayoutOptions>& FloorLayoutOptions::Table() {
  using O = FloorLayoutOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("rooms_per_side", &O::rooms_per_side, 4, "", R::Closed(1, 8), "rooms along each side of the corridor")
          .Add("corridor_width_m", &O::corridor_width_m, 2.4, "m", R::Closed(2.0, 5.0),
               "the corridor's width between its walls (the route runs in two lanes 0.6 m from them)")
          .Add("wall_thickness_m", &O::wall_thickness_m, 0.12, "m", R::Closed(0.05, 0.5),
               "thickness of the interior walls")
          .Add("door_width_m", &O::door_width_m, 1.3, "m", R::Closed(1.0, 3.0),
               "width of each room's two doorways onto the corridor (the route drives through them)")
          .Add("height_m", &O::height_m, 2.8, "m", R::Closed(2.5, 3.2), "the floor's ceiling height, every room's")
          .Add("north_depth_m", &O::north_depth_m, 5.6, "m", R::Closed(3.4, 8.0),
               "depth of the rooms north of the corridor: only families whose width range holds it are drawn there")
          .Add("south_depth_m", &O::south_depth_m, 5.0, "m", R::Closed(3.2, 8.0),
               "depth of the rooms south of the corridor (meeting_row rooms are at most 5 m deep, open_office at least "
               "5.6)")
          .Add("room_length_max_m", &O::room_length_max_m, 9.0, "m", R::Closed(5.0, 15.0),
               "longest room along the corridor (each family's length range is cut to it)")
          .Add("turnover_probability", &O::turnover_probability, 0.3, "", R::Closed(0, 1),
               "the floor's crowd.turnover_probability: at every lap people leave, arrive and change seats");
  return table;
}

}  // namespace hoilcd
