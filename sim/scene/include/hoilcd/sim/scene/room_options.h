// The room and its furniture as typed options (the scene's /room and /furniture): size, air and
// surface temperatures, windows, and how chairs are set around the tables. Each struct has one
// option table giving every field's JSON name, default, range and unit, the same as the schema.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

// A plain surface (floor, ceiling, a window pane).
struct SurfaceSpec {
  double temperature_c = 22;  // C
  double emissivity = 0.92;   // (0, 1]
  bool specular = false;      // mirror-like reflection instead of diffuse
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
  std::string wall;  // north | south | east | west
  double center_m = 0, bottom_m = 0, width_m = 0, height_m = 0;  // m, along the wall / above the floor
  SurfaceSpec surface;
  static const OptionTable<WindowSpec>& Table();  // one element of /room/windows
};

// A doorway walkers enter and leave by: its centre on a wall and its width.
struct DoorSpec {
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();  // on a wall (x = 0 or size_x, or y = 0 or size_y)
  double width_m = 0.9;                                  // clear width, m
};

struct RoomOptions {
  Eigen::Vector3d size_m;             // m, x (length), y (width), z (height)
  double environment_temperature_c;   // C, the air (and what surfaces reflect)
  SurfaceSpec floor, ceiling;
  WallOptions walls;
  std::vector<WindowSpec> windows;    // read by hand (an array); default: the schema's window
  std::vector<DoorSpec> doors;        // read by hand; a loaded scene's is never empty (one in the
                                      // middle of each end wall when the scene names none)
  RoomOptions();
  static const OptionTable<RoomOptions>& Table();
};

struct FurnitureOptions {
  std::string table_asset;      // asset name or path (resolved to a path when the scene loads)
  std::string chair_asset;
  double seat_setback_m;        // m, chair seat centre behind the table edge
  double seat_spacing_4_m;      // m, between seat centres at a table seating 4
  double seat_spacing_6_m;      // m, the same at a table seating 6
  double chair_jitter_m;        // m, sd of a chair's offset from its nominal place
  double chair_jitter_deg;      // deg, sd of a chair's yaw from square
  double seat_warmth_c;         // C, steady excess of a seat's print under a sitter (contact_heat.md)
  FurnitureOptions();
  static const OptionTable<FurnitureOptions>& Table();
};

}  // namespace hoilcd
