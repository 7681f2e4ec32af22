#include "hoilcd/sim/scene/room_options.h"

namespace hoilcd {

OptionTable<SurfaceSpec> SurfaceSpec::TableWith(double temperature_c, double emissivity, bool specular) {
  using O = SurfaceSpec;
  return OptionTable<O>()
      .Add("temperature_c", &O::temperature_c, temperature_c, "C", OptionRange::Closed(-50, 200),
           "surface temperature")
      .Add("emissivity", &O::emissivity, emissivity, "", OptionRange().Above(0).AtMost(1), "emissivity (8-14 um)")
      .Add("specular", &O::specular, specular,
           "mirror-like in LWIR: one traced reflection ray instead of ambient reflection");
}

WallOptions::WallOptions() { Table().FillDefaults(this); }

const OptionTable<WallOptions>& WallOptions::Table() {
  using O = WallOptions;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("temperature_bottom_c", &O::temperature_bottom_c, 21.0, "C", OptionRange::Closed(-50, 200),
               "wall temperature at the floor")
          .Add("temperature_top_c", &O::temperature_top_c, 23.5, "C", OptionRange::Closed(-50, 200),
               "wall temperature at the ceiling")
          .Add("emissivity", &O::emissivity, 0.92, "", OptionRange().Above(0).AtMost(1), "emissivity (8-14 um)")
          .Add("specular", &O::specular, false, "mirror-like in LWIR");
  return table;
}

const OptionTable<WindowSpec>& WindowSpec::Table() {
  using O = WindowSpec;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("wall", &O::wall, "north", {"north", "south", "east", "west"}, "the wall the window is set into")
          .Add("center_m", &O::center_m, 1.0, "m", OptionRange().AtLeast(0), "window centre along its wall")
          .Add("bottom_m", &O::bottom_m, 0.9, "m", OptionRange().AtLeast(0), "sill height above the floor")
          .Add("width_m", &O::width_m, 1.2, "m", OptionRange().Above(0), "window width")
          .Add("height_m", &O::height_m, 1.2, "m", OptionRange().Above(0), "window height")
          .Flatten(&O::surface, SurfaceSpec::TableWith(15.0, 0.94, true));
  return table;
}

RoomOptions::RoomOptions() : size_m(7.0, 3.0, 2.6) {
  Table().FillDefaults(this);
  // The schema's default window: one cold window in the north wall.
  WindowSpec north;
  WindowSpec::Table().FillDefaults(&north);
  north.center_m = 1.8;
  north.width_m = 1.6;
  north.height_m = 1.3;
  windows = {north};
}

const OptionTable<RoomOptions>& RoomOptions::Table() {
  using O = RoomOptions;
  static const OptionTable<O> table =
      OptionTable<O>()
          .External("size_m", "m, room size (x, y, z), each in (0, 100]")
          .Add("environment_temperature_c", &O::environment_temperature_c, 22.0, "C", OptionRange::Closed(-50, 200),
               "mean radiant temperature of the surroundings (ambient radiance for diffuse reflection)")
          .Nest("floor", &O::floor, SurfaceSpec::TableWith(21.5, 0.93, false))
          .Nest("ceiling", &O::ceiling, SurfaceSpec::TableWith(23.0, 0.91, false))
          .Nest("walls", &O::walls, WallOptions::Table())
          .External("windows", "cold windows set into walls (glass: opaque and reflective in LWIR)")
          .External("doors", "doorways walkers enter and leave by (none: one in the middle of each end wall)");
  return table;
}

FurnitureOptions::FurnitureOptions() { Table().FillDefaults(this); }

const OptionTable<FurnitureOptions>& FurnitureOptions::Table() {
  using O = FurnitureOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("table_asset", &O::table_asset, "table", {}, "asset name or glTF path of tables")
          .Add("chair_asset", &O::chair_asset, "chair", {}, "asset name or glTF path of chairs")
          .Add("seat_setback_m", &O::seat_setback_m, 0.15, "m", R::Closed(0, 2),
               "chair seat centre distance outside the table's long edge")
          .Add("seat_spacing_4_m", &O::seat_spacing_4_m, 0.45, "m", R::Closed(0, 3),
               "spacing of the 2 seats per side when people_per_table <= 4")
          .Add("seat_spacing_6_m", &O::seat_spacing_6_m, 0.45, "m", R::Closed(0, 3),
               "spacing of the 3 seats per side when people_per_table > 4")
          .Add("chair_jitter_m", &O::chair_jitter_m, 0.05, "m", R::Closed(0, 0.2),
               "each chair is shifted by up to this much along the table and pushed in by up to half of it")
          .Add("chair_jitter_deg", &O::chair_jitter_deg, 12.0, "deg", R::Closed(0, 45),
               "each chair is also turned by up to this much either way")
          .Add("seat_warmth_c", &O::seat_warmth_c, 2.0, "C", R::Closed(0, 20),
               "steady excess of the print a sitter warms on a chair seat (body heat through the plastic)");
  return table;
}

}  // namespace hoilcd
