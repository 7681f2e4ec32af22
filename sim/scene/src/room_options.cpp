#include "hoilcd/sim/scene/room_options.h"

namespace hoilcd {

OptionTable<SurfaceSpec> SurfaceSpec::TableWith(double temperature_c, double emissivity, bool specular) {
  using O = SurfaceSpec;
  return OptionTable<O>()
      .Add("temperature_c", &O::temperature_c, temperature_c, "C", OptionRange::Closed(-50, 200), "surface temperature")
      .Add("emissivity", &O::emissivity, emissivity, "", OptionRange().Above(0).AtMost(1), "emissivity (8-14 um)")
      .Add("specular", &O::specular, specular,
           "mirror-like in LWIR: one traced reflection ray instead of ambient reflection")
      .Add(
          "roughness_um", &O::roughness_um, 0.0, "um", OptionRange::Closed(0, 100),
          "with specular: rms surface roughness; the mirror-like share of the reflection is exp(-(4π·roughness·cos θ / "
          "10 µm)²) (Davies 1954), the rest diffuse: 0 for glass, ~0.5 for vinyl, ~1 for polished concrete "
          "(docs/models/sensor_and_thermal.md)");
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
          .Flatten(&O::surface, SurfaceSpec::TableWith(15.0, 0.94, true))
          .Add("u_value_w_m2k", &O::u_value_w_m2k, 2.8, "W/(m2 K)", OptionRange::Closed(0.3, 6.5),
               "glazing U-value (centre of glass): sets the glass temperature when room.surfaces.glass_from_u_value "
               "(single 5.8, old double 2.8, low-e double 1.1)");
  return table;
}

RoomSurfaceOptions::RoomSurfaceOptions() { Table().FillDefaults(this); }

const OptionTable<RoomSurfaceOptions>& RoomSurfaceOptions::Table() {
  using O = RoomSurfaceOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("thermal_bridges", &O::thermal_bridges, true,
               "edges and corners of outside walls are cooler (thermal bridges, ISO 10211 / ISO 13788)")
          .Add("exterior_walls", &O::exterior_walls, "windowed", {"windowed", "all", "none"},
               "which walls face outdoors: those with a window, all four, or none")
          .Add("wall_u_value_w_m2k", &O::wall_u_value_w_m2k, 0.6, "W/(m2 K)", R::Closed(0.1, 3),
               "U-value of an outside wall away from its edges")
          .Add("edge_f_rsi", &O::edge_f_rsi, 0.8, "", R().Above(0).Below(1),
               "temperature factor f_Rsi = (T_si - T_e) / (T_i - T_e) at an edge of an outside wall")
          .Add("bridge_decay_m", &O::bridge_decay_m, 0.15, "m", R().Above(0).AtMost(2),
               "distance over which an edge's cooling falls by 1/e")
          .Add("radiator_plume", &O::radiator_plume, true, "the wall above each radiator is warmer")
          .Add("plume_warming_k", &O::plume_warming_k, 4.0, "K", R::Closed(0, 30),
               "warming of the wall just above a radiator's top")
          .Add("plume_height_m", &O::plume_height_m, 0.6, "m", R().Above(0).AtMost(5),
               "height over which the plume's warming falls by 1/e")
          .Add("plume_spread_m", &O::plume_spread_m, 0.1, "m", R().Above(0).AtMost(2),
               "sideways fall-off (Gaussian sd) beyond the radiator's ends, growing by a quarter of the height")
          .Add("glass_from_u_value", &O::glass_from_u_value, true,
               "glass temperature T_i - U R_si (T_i - T_e) from each window's u_value_w_m2k (else its temperature_c)")
          .Add("window_frames", &O::window_frames, true, "frames between glass and wall")
          .Add("frame_width_m", &O::frame_width_m, 0.07, "m", R::Closed(0, 0.3), "visible frame width")
          .Add("frame_u_value_w_m2k", &O::frame_u_value_w_m2k, 1.8, "W/(m2 K)", R::Closed(0.3, 6.5),
               "frame U-value (PVC or wood frames 1.3-2.0, ISO 10077-1)")
          .Add("texture", &O::texture, true, "walls, ceiling and floor are not perfectly even")
          .Add("texture_k", &O::texture_k, 0.15, "K", R::Closed(0, 2), "amplitude of the irregularity")
          .Add("texture_scale_m", &O::texture_scale_m, 0.4, "m", R().Above(0).AtMost(10),
               "feature size of the irregularity");
  return table;
}

SunOptions::SunOptions() { Table().FillDefaults(this); }

const OptionTable<SunOptions>& SunOptions::Table() {
  using O = SunOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("enabled", &O::enabled, true, "sun patches where direct sun falls through a window")
          .Add("time_of_day_h", &O::time_of_day_h, 10.0, "h", R().AtLeast(0).Below(24),
               "local solar time at the sequence's start")
          .Add("day_of_year", &O::day_of_year, 20, "", R::Closed(1, 365), "day of the year (20: 20 January)")
          .Add("latitude_deg", &O::latitude_deg, 35.7, "deg", R::Closed(-66, 66), "latitude, north positive")
          .Add("north_wall_azimuth_deg", &O::north_wall_azimuth_deg, 0.0, "deg", R::Closed(-360, 360),
               "compass direction (clockwise from true north) of the room's +y axis, which the north wall faces")
          .Add("glass_transmittance", &O::glass_transmittance, 0.7, "", R().Above(0).AtMost(1),
               "direct solar transmittance of the glazing")
          .Add("warming_k_per_kw_m2", &O::warming_k_per_kw_m2, 12.0, "K/(kW/m2)", R::Closed(0, 100),
               "surface warming per kW/m2 of direct sun on it");
  return table;
}

HvacOptions::HvacOptions() { Table().FillDefaults(this); }

const OptionTable<HvacOptions>& HvacOptions::Table() {
  using O = HvacOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("enabled", &O::enabled, true, "the air cycles through the thermostat's deadband; surfaces follow")
          .Add("deadband_k", &O::deadband_k, 1.0, "K", R::Closed(0, 5), "peak-to-peak swing of the air temperature")
          .Add("period_s", &O::period_s, 900.0, "s", R().Above(0).AtMost(86400), "one heating and one cooling phase")
          .Add("heating_fraction", &O::heating_fraction, 0.5, "", R().Above(0).Below(1),
               "share of a cycle the air warms")
          .Add("surface_lag_s", &O::surface_lag_s, 600.0, "s", R::Closed(0, 86400),
               "first-order time constant with which surfaces (and what they reflect) follow the air");
  return table;
}

ThermalSolutionOptions::ThermalSolutionOptions() { Table().FillDefaults(this); }

const OptionTable<ThermalSolutionOptions>& ThermalSolutionOptions::Table() {
  using O = ThermalSolutionOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("enabled", &O::enabled, true,
               "solve every static surface's energy balance (convection, radiation exchange by view factors, "
               "conduction outdoors, heat capacity) instead of the per-surface estimates")
          .Add("patch_size_m", &O::patch_size_m, 0.25, "m", R::Closed(0.05, 2),
               "side of a wall, floor or ceiling patch")
          .Add("rays_per_node", &O::rays_per_node, 256, "", R::Closed(16, 65536),
               "view-factor rays cast from each node")
          .Add("step_s", &O::step_s, 60.0, "s", R::Closed(1, 3600), "time step of the solution (frames interpolate)")
          .Add("spin_up_s", &O::spin_up_s, 21600.0, "s", R::Closed(0, 604800),
               "history solved before the sequence starts, from a steady state")
          .Add("air_gradient_k_per_m", &O::air_gradient_k_per_m, 0.8, "K/m", R::Closed(-5, 5),
               "vertical air temperature gradient about the room's mid-height")
          .Add("convection_wall_w_m2k", &O::convection_wall_w_m2k, 2.5, "W/(m2 K)", R::Closed(0, 50),
               "convective coefficient of walls and windows (ISO 6946, horizontal heat flow)")
          .Add("convection_floor_w_m2k", &O::convection_floor_w_m2k, 0.7, "W/(m2 K)", R::Closed(0, 50),
               "convective coefficient of the floor (ISO 6946, heat flowing down)")
          .Add("convection_ceiling_w_m2k", &O::convection_ceiling_w_m2k, 5.0, "W/(m2 K)", R::Closed(0, 50),
               "convective coefficient of the ceiling (ISO 6946, heat flowing up)")
          .Add("convection_object_w_m2k", &O::convection_object_w_m2k, 3.0, "W/(m2 K)", R::Closed(0, 50),
               "convective coefficient of furniture and objects")
          .Add("capacity_wall_j_m2k", &O::capacity_wall_j_m2k, 30000.0, "J/(m2 K)", R::Closed(0, 1e7),
               "effective areal heat capacity of walls")
          .Add("capacity_floor_j_m2k", &O::capacity_floor_j_m2k, 40000.0, "J/(m2 K)", R::Closed(0, 1e7),
               "effective areal heat capacity of the floor")
          .Add("capacity_ceiling_j_m2k", &O::capacity_ceiling_j_m2k, 30000.0, "J/(m2 K)", R::Closed(0, 1e7),
               "effective areal heat capacity of the ceiling")
          .Add("capacity_glass_j_m2k", &O::capacity_glass_j_m2k, 17000.0, "J/(m2 K)", R::Closed(0, 1e7),
               "areal heat capacity of the glazing (two 4 mm panes)")
          .Add("capacity_object_j_m2k", &O::capacity_object_j_m2k, 10000.0, "J/(m2 K)", R::Closed(0, 1e7),
               "effective areal heat capacity of furniture and objects")
          .Add("solar_absorptance_floor", &O::solar_absorptance_floor, 0.6, "", R::Closed(0, 1),
               "share of the transmitted sun a floor absorbs (ISO 52016-1's default for opaque surfaces)")
          .Add("solar_absorptance_walls", &O::solar_absorptance_walls, 0.3, "", R::Closed(0, 1),
               "share of the transmitted sun light-painted walls and the ceiling absorb (white paint 0.2-0.3)")
          .Add("solar_absorptance_object", &O::solar_absorptance_object, 0.6, "", R::Closed(0, 1),
               "share of the transmitted sun furniture and objects absorb");
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
          .Add("outdoor_temperature_c", &O::outdoor_temperature_c, 5.0, "C", OptionRange::Closed(-50, 50),
               "outdoor air temperature: sets cold glass, frames and thermal bridges")
          .Nest("floor", &O::floor, SurfaceSpec::TableWith(21.5, 0.93, false))
          .Nest("ceiling", &O::ceiling, SurfaceSpec::TableWith(23.0, 0.91, false))
          .Nest("walls", &O::walls, WallOptions::Table())
          .Nest("surfaces", &O::surfaces, RoomSurfaceOptions::Table())
          .Nest("sun", &O::sun, SunOptions::Table())
          .Nest("hvac", &O::hvac, HvacOptions::Table())
          .Nest("thermal", &O::thermal, ThermalSolutionOptions::Table())
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
