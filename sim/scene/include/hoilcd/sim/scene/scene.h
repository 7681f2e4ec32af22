// Scene files: JSON validated against scenes/scene.schema.json (embedded in the binary), with
// command-line overrides (--set KEY=VALUE) applied first and every default filled in from the
// schema, so the resolved scene is complete. The typed Scene is what the simulator reads.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "hoilcd/core/util/error.h"
#include "hoilcd/sim/people/crowd_options.h"
#include "hoilcd/sim/robot/robot.h"
#include "hoilcd/sim/scene/building_floor.h"
#include "hoilcd/sim/scene/camera_options.h"
#include "hoilcd/sim/scene/room_options.h"

namespace hoilcd {

// The scene JSON Schema text (scenes/scene.schema.json, compiled in), and the same parsed once.
const std::string& SceneSchemaText();
const nlohmann::json& SceneSchema();

// Applies one "KEY=VALUE" override. KEY is a dotted path ("crowd.people_per_table",
// "tables.0.center_m") or a JSON pointer ("/crowd/people_per_table"); VALUE is parsed as JSON
// when it is valid JSON, else taken as a string. Throws InputError naming the override.
void ApplyOverride(nlohmann::json* doc, const std::string& key_equals_value);

// Every schema violation of doc, each as {file: /json/pointer, what was expected}.
std::vector<Problem> ValidateScene(const nlohmann::json& doc, const std::string& file);

// Inserts schema defaults for every absent property, recursively.
void FillSceneDefaults(nlohmann::json* doc);

// How a table's seats are set (the schema's /tables/N/seats says where each stands).
enum class SeatArrangement { kBothSides, kOneSide, kAround, kSofa, kNone };

struct TableSpec {
  Eigen::Vector2d center_m = Eigen::Vector2d::Zero();
  double yaw_deg = 0;
  std::string asset;  // asset name or path; "" when the scene names none (furniture.table_asset)
  SeatArrangement seats = SeatArrangement::kBothSides;
  int seat_count = 0;  // seats of kOneSide, kAround and kSofa (their default when the scene names none)
};

// The seat indices a table offers: both sides, per_side seats each (0.. on -y, 3.. on +y, as
// people_per_table sets them); otherwise 0 .. seat_count - 1 (none for kNone).
std::vector<int> SeatsOf(const TableSpec& table, int per_side);

struct ObjectSpec {
  std::string asset;
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  double yaw_deg = 0;
  double temperature_offset_c = 0;
  bool enabled = true;
};

// One recording run of /runs, resolved (docs/guide/runs.md).
struct RunSpec {
  double time_of_day_h = 10;           // h, local solar time at the run's start
  int day = 0;                         // days after the first run's day
  int frames = 0;                      // frames of the run
  uint64_t seed = 0;                   // the run's seed (Scene::run_seed of its scene)
  std::vector<std::string> overrides;  // /runs/N/set as "KEY=VALUE", applied to the run's scene only
  double start_time_s = 0;             // s, its start after the first run's
};

// The typed, fully resolved scene. Field meanings and units: scenes/scene.schema.json.
struct Scene {
  std::string file;                   // where it was loaded from (for messages)
  nlohmann::json resolved;            // the resolved document (dataset's scene.json)
  std::string hash;                   // checksum of the resolved document
  std::string assets_dir;             // absolute folder searched for asset names
  std::vector<std::string> warnings;  // what it may not mean: a --set camera profile's values the file sets

  std::string name;
  uint64_t seed = 1;
  int frames = 1996;
  double frame_rate_hz = 25;

  RoomOptions room;  // /room
  FloorPlan floor;   // /floor: rooms and interior walls (empty: one room)
  std::vector<TableSpec> tables;
  FurnitureOptions furniture;  // /furniture (asset names resolved to paths)

  CrowdOptions crowd;  // /crowd

  std::vector<ObjectSpec> objects;  // distractor switches already applied
  CameraOptions camera;             // /camera: image, sensor, renderer, video
  TricycleOptions robot;            // /robot
  RouteOptions route;               // /route (frames = the scene's frames)
  OdometryErrorOptions odometry;    // /odometry
  // /runs: the recording runs, each rendered from SceneOfRun (empty: one run, this scene; then
  // frames is the sequence's, else the runs' total).
  std::vector<RunSpec> runs;
  uint64_t run_seed = 1;  // what differs between runs (crowd, robot and camera noise) draws from it: seed, or the run's
  double clock_offset_s = 0;  // s, this run's start after the first run's (the HVAC cycle runs on through it)
};

// Run k of a scene with /runs, as a scene of one run: its /runs/k/set overrides applied, its frames,
// time of day (room.sun.time_of_day_h, day_of_year counted on by its day), run_seed and
// clock_offset_s; the scene itself when it has no runs (k = 0). Throws InputError at /runs/k.
Scene SceneOfRun(const Scene& scene, int k);
// `error`, found in run k's scene, as problems at /runs/k (itself when the scene has no runs).
InputError LocatedInRun(const Scene& scene, int k, const InputError& error);

// Reads, overrides, validates (all problems at once), fills defaults, and types a scene file.
// Throws InputError listing every problem as "FILE: /json/pointer: what was expected".
Scene LoadScene(const std::string& path, const std::vector<std::string>& overrides = {});

// `error` with every problem given as a bare scene section ("route", "frame_rate_hz") located
// in the scene file ("FILE: /route"): for checks made while simulating, not while loading.
InputError LocatedInScene(const Scene& scene, const InputError& error);

// The same from an in-memory document (file names messages).
Scene SceneFromJson(nlohmann::json doc, const std::string& file, const std::vector<std::string>& overrides = {});

}  // namespace hoilcd
