// The room and its furniture as typed options (the scene's /room and /furniture): size, air and
// surface temperatures, windows, and how chairs are set around the tables. Each struct has one
// option table giving every field's JSON name, default, range and unit, the same as the schema.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

// A plain surface (floor, ceiling, a window pane).
struct SurfaceSpec {
  double temperature_c = 22;  // C
  double emissivity = 0.92;   // (0, 1]
  bool specular = false;      // mirror-like reflection instead of diffuse
  double roughness_um = 0;    // with specular: rms roughness, µm (0: a perfect mirror)
  // The table of a surface whose defaults are these (floor and ceiling differ only in defaults).
  static OptionTable<SurfaceSpec> TableWith(double temperature_c, double emissivity, bool specular);
};

// The walls: temperature graded linearly from floor to ceiling.
struct WallOptions {
  double temperature_bottom_c;  // C, at the floor
  double temperature_top_c;     // C, at the ceiling
  double emissivity;            // (0, 1]
  bool specular;
  WallOptions();
  static const OptionTable<WallOptions>& Table();
};

struct WindowSpec {
  std::string wall;                                              // north | south | east | west
  double center_m = 0, bottom_m = 0, width_m = 0, height_m = 0;  // m, along the wall / above the floor
  SurfaceSpec surface;
  double u_value_w_m2k = 2.8;  // W/(m²·K), glazing; sets the glass temperature with room.surfaces.glass_from_u_value
  static const OptionTable<WindowSpec>& Table();  // one element of /room/windows
};

// A doorway walkers enter and leave by: its centre on a wall and its width.
struct DoorSpec {
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();  // on a wall (x = 0 or size_x, or y = 0 or size_y)
  double width_m = 0.9;                                  // clear width, m
};

// What makes walls, ceiling, floor and windows vary inside one surface (room_surfaces.md).
struct RoomSurfaceOptions {
  bool thermal_bridges;        // cooler edges and corners of outside walls
  std::string exterior_walls;  // "windowed" (walls with a window) | "all" | "none"
  double wall_u_value_w_m2k;   // W/(m²·K), outside wall away from edges
  double edge_f_rsi;           // temperature factor f_Rsi at an edge (ISO 13788), (0, 1)
  double bridge_decay_m;       // m, e-folding distance of an edge's cooling
  bool radiator_plume;         // warm wall above each radiator
  double plume_warming_k;      // K, at the radiator's top
  double plume_height_m;       // m, e-folding height of the plume
  double plume_spread_m;       // m, sideways fall-off beyond the radiator's ends
  bool glass_from_u_value;     // glass temperature from its U-value and the outdoor temperature
  bool window_frames;          // frames between glass and wall
  double frame_width_m;        // m
  double frame_u_value_w_m2k;  // W/(m²·K)
  bool texture;                // small smooth irregularity (a fraction of a kelvin)
  double texture_k;            // K, amplitude
  double texture_scale_m;      // m, feature size
  RoomSurfaceOptions();
  static const OptionTable<RoomSurfaceOptions>& Table();
};

// The sun through the windows: a warm patch where it falls (room_surfaces.md).
struct SunOptions {
  bool enabled;
  double time_of_day_h;           // h, local solar time at the sequence's start
  int day_of_year;                // 1..365
  double latitude_deg;            // deg, north positive
  double north_wall_azimuth_deg;  // deg, compass direction the room's +y ("north") axis points
  double glass_transmittance;     // (0, 1], direct solar transmittance of the glazing
  double warming_k_per_kw_m2;     // K per kW/m² of sun absorbed on a surface
  SunOptions();
  static const OptionTable<SunOptions>& Table();
};

// The thermostat's cycle: the air swings through the deadband, the surfaces follow slowly.
struct HvacOptions {
  bool enabled;
  double deadband_k;        // K, peak to peak of the air's swing
  double period_s;          // s, one heating and one cooling phase
  double heating_fraction;  // (0, 1), share of a cycle the air warms
  double surface_lag_s;     // s, first-order time constant of the surfaces
  HvacOptions();
  static const OptionTable<HvacOptions>& Table();
};

// The thermal solution of the room's static surfaces (thermal_solution.md): patches, view
// factors, air, convection and heat capacities.
struct ThermalSolutionOptions {
  bool enabled;                     // solve every static surface's energy balance
  double patch_size_m;              // m, side of a wall, floor or ceiling patch
  int rays_per_node;                // view-factor rays cast from each node
  double step_s;                    // s, the time grid
  double spin_up_s;                 // s, history solved before t = 0
  double air_gradient_k_per_m;      // K/m, the air's stratification
  double convection_wall_w_m2k;     // W/(m²·K), h_c of vertical surfaces (ISO 6946)
  double convection_floor_w_m2k;    // W/(m²·K), h_c of the floor (heat flowing down)
  double convection_ceiling_w_m2k;  // W/(m²·K), h_c of the ceiling (heat flowing up)
  double convection_object_w_m2k;   // W/(m²·K), h_c of furniture and objects
  double capacity_wall_j_m2k;       // J/(m²·K), effective areal heat capacity
  double capacity_floor_j_m2k;
  double capacity_ceiling_j_m2k;
  double capacity_glass_j_m2k;
  double capacity_object_j_m2k;
  double solar_absorptance_floor;   // share of the sun's short-wave light a floor absorbs
  double solar_absorptance_walls;   // the same for walls and the ceiling
  double solar_absorptance_object;  // the same for furniture and objects
  ThermalSolutionOptions();
  static const OptionTable<ThermalSolutionOptions>& Table();
};

struct RoomOptions {
  Eigen::Vector3d size_m;            // m, x (length), y (width), z (height)
  double environment_temperature_c;  // C, the air (and what surfaces reflect)
  double outdoor_temperature_c;      // C, outside air (glass, frames, thermal bridges)
  RoomSurfaceOptions surfaces;
  SunOptions sun;
  HvacOptions hvac;
  ThermalSolutionOptions thermal;
  SurfaceSpec floor, ceiling;
  WallOptions walls;
  std::vector<WindowSpec> windows;  // read by hand (an array); default: the schema's window
  std::vector<DoorSpec> doors;      // read by hand; a loaded scene's is never empty (one in the
                                    // middle of each end wall when the scene names none)
  RoomOptions();
  static const OptionTable<RoomOptions>& Table();
};

struct FurnitureOptions {
  std::string table_asset;  // asset name or path (resolved to a path when the scene loads)
  std::string chair_asset;
  double seat_setback_m;    // m, chair seat centre behind the table edge
  double seat_spacing_4_m;  // m, between seat centres at a table seating 4
  double seat_spacing_6_m;  // m, the same at a table seating 6
  double chair_jitter_m;    // m, sd of a chair's offset from its nominal place
  double chair_jitter_deg;  // deg, sd of a chair's yaw from square
  double seat_warmth_c;     // C, steady excess of a seat's print under a sitter (contact_heat.md)
  FurnitureOptions();
  static const OptionTable<FurnitureOptions>& Table();
};

}  // namespace hoilcd
