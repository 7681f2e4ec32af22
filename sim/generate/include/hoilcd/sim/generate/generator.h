// A seeded generator of varied rooms (`hoilcd generate`): six layout families, each with its own
// furniture and seating rules, a room size, people drawn within the crowd schema, and a closed
// robot route planned around the furniture with clearance. Same arguments, same bytes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hoilcd/core/util/option_table.h"
#include "hoilcd/sim/scene/scene.h"
#include "hoilcd/sim/world/world.h"

namespace hoilcd {

// The layout families, in the order `mixed` draws from.
const std::vector<std::string>& LayoutFamilies();
// Bumped whenever the same arguments would give other scenes; recorded in every scene.
// Version 2: rooms hold doors in frames, switches, sockets, a whiteboard, an air conditioner,
// shelves, cabinets, ceiling lights, and bags, coats and chargers by occupied seats.
// Version 3: the floor is matte or one of four glossy finishes (room.floor.roughness_um).
// Version 4: the clutter of lived-in rooms (objects.clutter_density, 1 by default); at density 0
// a room is version 3's.
constexpr int kGeneratorVersion = 4;

// A family's room size, drawn uniformly per scene: length along x, width along y.
struct RoomSizeRange {
  double length_min_m, length_max_m;  // m
  double width_min_m, width_max_m;    // m
};

// The things a room holds besides its furniture (the scene's /generator/options/objects);
// docs/guide/generate.md says where each goes.
struct RoomObjectOptions {
  double whiteboard_probability;   // a whiteboard on the front (west) wall of classroom, seminar_u, meeting_row
  double ac_unit_probability;      // an air conditioner high on the south or east wall
  double socket_probability;       // a wall socket on the nearer long wall, per table or desk
  int shelf_count_max;             // wall shelves, uniform in 0..this
  int cabinet_count_max;           // floor cabinets against free wall, uniform in 0..this
  double ceiling_light_spacing_m;  // m, pitch of the ceiling lights' grid
  double bag_probability;          // a bag on the floor beside an occupied chair
  double coat_probability;         // a coat over an occupied chair's backrest
  double charger_probability;      // a charger on the table top beside an occupied seat
  double clutter_density;          // the clutter of lived-in rooms: 0 none, 1 typical (docs/guide/generate.md)

  static const OptionTable<RoomObjectOptions>& Table();
};

// The building floor of `--layout floor` (the scene's /generator/options/floor): generated rooms of
// the six families side by side along both sides of a corridor (docs/guide/floor.md).
struct FloorLayoutOptions {
  int rooms_per_side;           // rooms along each side of the corridor
  double corridor_width_m;      // m, between the corridor's walls
  double wall_thickness_m;      // m, of the interior walls
  double door_width_m;          // m, each room's two doorways onto the corridor
  double height_m;              // m, the floor's ceiling height (every room's)
  double north_depth_m;         // m, depth of the rooms north of the corridor
  double south_depth_m;         // m, depth of the rooms south of it
  double room_length_max_m;     // m, longest room along the corridor
  double turnover_probability;  // the floor's crowd.turnover_probability (the crowd changes each lap)

  static const OptionTable<FloorLayoutOptions>& Table();
};

// Every parameter of the generator but the layout, seed and count (the scene's /generator/options).
struct GeneratorOptions {
  RoomSizeRange meeting_row, classroom, cafeteria, open_office, seminar_u, lounge;
  double height_min_m, height_max_m;              // m, room height, uniform
  double occupancy_min, occupancy_max;            // fraction of seats taken, uniform per room
  double posture_weight_min, posture_weight_max;  // each seated posture's weight, uniform
  double activity_weight_spread;                  // each activity weight times U[1 - s, 1 + s]
  int walkers_max;                                // walkers per room, uniform in 0..walkers_max
  double turnover_max;                            // crowd.turnover_probability, uniform in [0, this]
  double glossy_floor_probability;                // a glossy floor finish, else matte
  double laps;                                    // laps the robot drives (sets the frames)
  double route_wall_m;                            // m, route from the walls
  double route_clearance_m;                       // m, route centre line from every footprint
  int attempts;                                   // draws of a scene before it is given up
  RoomObjectOptions objects;                      // doors, wall and ceiling fittings, people's things
  FloorLayoutOptions floor;                       // --layout floor: the building's plan

  GeneratorOptions();  // the registered defaults
  // Every field once: JSON name (the scene's /generator/options), unit, default, range, description.
  static const OptionTable<GeneratorOptions>& Table();
  const RoomSizeRange& SizeOf(const std::string& family) const;
};

// The largest scene index of a run (--start, a suite's generate.index; the schema's
// /generator/index).
constexpr int kMaxGeneratedSceneIndex = 10000;

// Scene `index` of the run (seed, layout): layout is a family or "mixed" (the family drawn per
// index). A scene depends on (seed, index, family, options) only, so `--layout FAMILY` regenerates
// what `mixed` drew. Throws InputError when no draw in options.attempts passes every check.
nlohmann::ordered_json GenerateScene(const std::string& layout, uint64_t seed, int index,
                                     const GeneratorOptions& options);

// Scene `index` of `--layout floor`: a building floor of 2 x options.floor.rooms_per_side generated
// rooms joined by a corridor, with a closed route through every room (floor_layout.cpp).
nlohmann::ordered_json GenerateFloorScene(uint64_t seed, int index, const GeneratorOptions& options);

// The family scene `index` gets (layout itself unless it is "mixed"); InputError naming --layout
// when layout is neither a family nor "mixed".
std::string FamilyOf(const std::string& layout, uint64_t seed, int index);

// What the generator checks of every scene it makes, one sentence per problem (none: fine):
// footprints inside the room and apart (a chair may stand under its own table), every seat
// reachable on foot from the route's start, the route a closed clockwise loop keeping wall_m
// from the walls and clearance_m from every footprint, every object inside the room, wall-mounted
// ones touching a wall with their backs and ceiling lights touching the ceiling.
std::vector<std::string> GeneratedSceneProblems(const Scene& scene, const World& world, double wall_m,
                                                double clearance_m);

// A scene file's name in the output folder: "scene_0007_classroom.json".
std::string GeneratedSceneFileName(int index, const std::string& family);

// The bytes of a scene file: keys in a fixed order, two-space indent, a final newline.
std::string SceneFileText(const nlohmann::ordered_json& scene);

// The folder rule of generate -o: a missing or empty folder, or one holding only earlier
// generated scenes (JSON objects with a /generator object), is fine; else InputError naming the
// other entries.
void CheckGenerateFolder(const std::string& dir);

}  // namespace hoilcd
