// hoilcd generate's scenes: every layout family gives valid, collision-free scenes over 50 seeds
// (footprints inside the room and apart, seats reachable, the route a closed loop keeping its
// clearance, the robot's run clear of every footprint), the same bytes on every run, and what
// `mixed` draws is what the family alone gives.
#include "hoilcd/sim/generate/generator.h"

#include <filesystem>
#include <map>
#include <set>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/dataset/exr_io.h"
#include "hoilcd/core/util/file_io.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/sim/output/sequence.h"
#include "hoilcd/sim/scene/scene_options.h"
#include "processes.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

constexpr int kSeeds = 50;

Scene Load(const nlohmann::ordered_json& doc) {
  return SceneFromJson(nlohmann::json::parse(doc.dump()), "generated.json");
}

// The clutter's assets by where they go (docs/guide/generate.md); "" for every other asset.
std::string ClutterCategory(const std::string& asset) {
  for (const char* a : {"papers", "mug", "bottle", "desk_phone", "power_strip"})
    if (asset == a) return "table top";
  for (const char* a :
       {"skirting_board", "skirting_board_short", "window_sill", "blind", "heating_pipe", "cable_trunking",
        "thermostat", "return_grille", "supply_grille", "poster", "framed_picture", "notice_board", "wall_clock"})
    if (asset == a) return "wall";
  for (const char* a : {"bookcase", "pc_tower", "bin", "cardboard_box", "rug", "router"})
    if (asset == a) return "floor";
  for (const char* a : {"ceiling_diffuser", "smoke_detector", "sprinkler", "bulkhead"})
    if (asset == a) return "ceiling";
  if (asset == "book_row" || asset == "binder_row") return "shelf";
  return "";
}

class EveryLayout : public testing::TestWithParam<std::string> {};

TEST_P(EveryLayout, GivesValidCollisionFreeScenesWithReachableSeatsAndAClearClosedRouteOver50Seeds) {
  const GeneratorOptions options;
  std::vector<std::string> failures(kSeeds);
  std::vector<int> whiteboards(kSeeds, 0), people_things(kSeeds, 0);
  std::vector<std::map<std::string, int>> clutter(kSeeds);  // per seed, category: count
  ParallelFor(kSeeds, 0, [&](int64_t seed) {
    try {
      const nlohmann::ordered_json doc = GenerateScene(GetParam(), static_cast<uint64_t>(seed), 0, options);
      const Scene scene = Load(doc);
      const BandRadianceTable table;
      const World world(scene, table);
      std::string problems;
      for (const std::string& p : GeneratedSceneProblems(scene, world, options.route_wall_m, options.route_clearance_m))
        problems += p + "; ";
      const RobotRun run = SimulateSceneRobot(scene, world.obstacles());
      if (run.laps < options.laps - 0.01) problems += "the robot drove only " + std::to_string(run.laps) + " laps; ";
      if (scene.tables.empty() && scene.crowd.standing.empty()) problems += "an empty room; ";
      if (doc["generator"]["layout"] != GetParam()) problems += "generator.layout is not the family; ";
      // Every room has its doors in frames, a switch by each, and ceiling lights.
      std::map<std::string, int> count;
      for (const ObjectSpec& o : scene.objects) ++count[o.asset];
      if (count["door_frame"] != static_cast<int>(scene.room.doors.size())) problems += "a door without its frame; ";
      if (count["light_switch"] < 1 || count["ceiling_light"] < 1) problems += "no switch or no ceiling light; ";
      if (!problems.empty()) failures[static_cast<size_t>(seed)] = "seed " + std::to_string(seed) + ": " + problems;
      whiteboards[static_cast<size_t>(seed)] = count["whiteboard"];
      people_things[static_cast<size_t>(seed)] = count["bag"] + count["coat"] + count["charger"];
      for (const auto& [asset, n] : count) clutter[static_cast<size_t>(seed)][ClutterCategory(asset)] += n;
    } catch (const std::exception& e) {
      failures[static_cast<size_t>(seed)] = "seed " + std::to_string(seed) + ": " + e.what();
    }
  });
  for (const std::string& f : failures) EXPECT_EQ(f, "");
  // A whiteboard on the front wall of most classroom, seminar_u and meeting_row rooms (never
  // elsewhere); bags, coats or chargers in most rooms with chairs.
  const int with_whiteboard =
      static_cast<int>(std::count_if(whiteboards.begin(), whiteboards.end(), [](int n) { return n > 0; }));
  const bool front_wall = GetParam() == "classroom" || GetParam() == "seminar_u" || GetParam() == "meeting_row";
  if (front_wall) {
    EXPECT_GE(with_whiteboard, kSeeds * 7 / 10);
  } else {
    EXPECT_EQ(with_whiteboard, 0);
  }
  // The clutter (density 1, the default): walls, floors and ceilings in most rooms, bookcases'
  // shelves in some; table tops in some, but for meeting rows, whose tables are seated all round
  // (every seat's place is kept for its person's props and forearms).
  const std::map<std::string, int> least = {{"wall", kSeeds * 9 / 10},
                                            {"floor", kSeeds * 7 / 10},
                                            {"ceiling", kSeeds * 9 / 10},
                                            {"shelf", kSeeds / 10},
                                            {"table top", GetParam() == "meeting_row" ? 0 : kSeeds / 5}};
  for (const auto& [category, rooms_least] : least) {
    const int rooms =
        static_cast<int>(std::count_if(clutter.begin(), clutter.end(), [&](auto& c) { return c[category] > 0; }));
    EXPECT_GE(rooms, rooms_least) << category;
  }
  const int with_things =
      static_cast<int>(std::count_if(people_things.begin(), people_things.end(), [](int n) { return n > 0; }));
  if (GetParam() != "lounge") {
    EXPECT_GE(with_things, kSeeds / 2);
  }
}

INSTANTIATE_TEST_SUITE_P(Generator, EveryLayout, testing::ValuesIn(LayoutFamilies()),
                         [](const testing::TestParamInfo<std::string>& info) { return info.param; });

TEST(Generator, TheSameArgumentsGiveTheSameBytesAndMixedDrawsWhatTheFamilyGives) {
  const GeneratorOptions options;
  for (int index = 0; index < 6; ++index) {
    const std::string text = SceneFileText(GenerateScene("mixed", 11, index, options));
    EXPECT_EQ(text, SceneFileText(GenerateScene("mixed", 11, index, options)));
    const std::string family = FamilyOf("mixed", 11, index);
    EXPECT_EQ(text, SceneFileText(GenerateScene(family, 11, index, options))) << family;
    EXPECT_EQ(text.back(), '\n');
    EXPECT_EQ(text.rfind("{\n  \"name\": ", 0), 0u) << "keys in the generator's order, indented";
  }
  EXPECT_NE(SceneFileText(GenerateScene("classroom", 11, 0, options)),
            SceneFileText(GenerateScene("classroom", 12, 0, options)));
}

// At density 0 a room holds none of the clutter, and the rest of it is what density 1 gives (the
// clutter has its own stream): the same furniture, fittings and people's things.
TEST(Generator, AtClutterDensity0ARoomHoldsNoClutterAndTheRestIsUnchanged) {
  GeneratorOptions none;
  none.objects.clutter_density = 0;
  const GeneratorOptions typical;
  int same = 0;
  for (int index = 0; index < 6; ++index) {
    const nlohmann::ordered_json bare = GenerateScene("mixed", 5, index, none),
                                 full = GenerateScene("mixed", 5, index, typical);
    nlohmann::ordered_json kept = nlohmann::ordered_json::array();
    for (const auto& o : bare["objects"]) EXPECT_EQ(ClutterCategory(o["asset"]), "") << o["asset"];
    for (const auto& o : full["objects"])
      if (ClutterCategory(o["asset"]).empty()) kept.push_back(o);
    EXPECT_EQ(bare["tables"], full["tables"]);
    EXPECT_EQ(bare["crowd"], full["crowd"]);
    EXPECT_EQ(bare["route"], full["route"]);
    same += bare["objects"] == kept;
    EXPECT_GT(full["objects"].size(), bare["objects"].size() + 20) << "density 1 adds the clutter";
  }
  EXPECT_GE(same, 5) << "only a room that had to leave its floor objects out may differ";
}

// Twice the density gives more clutter than the typical room, half of it less (over six rooms).
TEST(Generator, TheClutterGrowsWithItsDensity) {
  auto clutter = [](double density) {
    GeneratorOptions o;
    o.objects.clutter_density = density;
    size_t n = 0;
    for (int index = 0; index < 6; ++index) {
      const nlohmann::ordered_json scene = GenerateScene("mixed", 9, index, o);
      for (const auto& obj : scene["objects"]) n += !ClutterCategory(obj["asset"]).empty();
    }
    return n;
  };
  const size_t half = clutter(0.5), one = clutter(1.0), twice = clutter(2.0);
  EXPECT_LT(half, one);
  EXPECT_LT(one, twice);
}

TEST(Generator, MixedDrawsEveryFamily) {
  std::set<std::string> drawn;
  for (int index = 0; index < 60; ++index) drawn.insert(FamilyOf("mixed", 1, index));
  EXPECT_EQ(drawn.size(), LayoutFamilies().size());
}

TEST(Generator, TheGeneratorObjectRecordsTheRunAndRenderingIgnoresIt) {
  GeneratorOptions options;
  options.occupancy_min = 0.9;
  const nlohmann::ordered_json doc = GenerateScene("seminar_u", 4, 3, options);
  const nlohmann::ordered_json& g = doc["generator"];
  EXPECT_EQ(g["layout"], "seminar_u");
  EXPECT_EQ(g["seed"], 4);
  EXPECT_EQ(g["index"], 3);
  EXPECT_EQ(g["version"], kGeneratorVersion);
  EXPECT_EQ(g["options"]["occupancy_min"], 0.9);
  // The scene without its generator object is the same world.
  nlohmann::ordered_json bare = doc;
  bare.erase("generator");
  const Scene with = Load(doc), without = Load(bare);
  const BandRadianceTable table;
  const World a(with, table), b(without, table);
  ASSERT_EQ(a.obstacles().size(), b.obstacles().size());
  for (size_t i = 0; i < a.obstacles().size(); ++i) {
    EXPECT_EQ(a.obstacles()[i].name, b.obstacles()[i].name);
    EXPECT_EQ(a.obstacles()[i].center_m, b.obstacles()[i].center_m);
  }
  EXPECT_EQ(a.people().size(), b.people().size());
}

// Issue 45, defect 1: a folder that cannot be listed (mode 333, here as user nobody) was taken as
// empty, and generate overwrote the scene files in it. It is refused, naming the folder.
TEST(Generator, AFolderItCannotListIsRefusedNotTakenAsEmpty) {
  const test::TestDir temp;
  const std::string dir = temp / "unlistable";
  fs::create_directories(dir);
  WriteFileAtomic(dir + "/scene_0000_lounge.json", "{\"the user's\": 1}");
  fs::permissions(temp.path(), fs::perms::all);  // nobody reaches the folder, and cannot list it
  fs::permissions(dir, fs::perms::owner_write | fs::perms::owner_exec | fs::perms::group_write | fs::perms::group_exec |
                           fs::perms::others_write | fs::perms::others_exec);
  const test::Unprivileged outcome = test::RunUnprivileged([&] {
    CheckGenerateFolder(dir);
    return std::string("accepted");
  });
  fs::permissions(dir, fs::perms::all);
  if (!outcome.dropped) GTEST_SKIP() << "cannot run as an unprivileged user here (" << outcome.result << ")";
  EXPECT_NE(outcome.result.find(dir + ": cannot list the folder (Permission denied)"), std::string::npos)
      << outcome.result;
  EXPECT_EQ(ReadFileBytes(dir + "/scene_0000_lounge.json"), "{\"the user's\": 1}");
}

// GeneratedSceneProblems' object rules: inside the room, wall objects' backs on a wall facing in,
// ceiling lights on the ceiling.
TEST(Generator, ObjectsOffTheirWallOrCeilingOrOutsideTheRoomAreProblems) {
  const nlohmann::ordered_json doc = GenerateScene("classroom", 3, 0, GeneratorOptions());
  auto problems_with = [&](const nlohmann::ordered_json& object) {
    nlohmann::ordered_json changed = doc;
    changed["objects"].push_back(object);
    const Scene scene = Load(changed);
    const BandRadianceTable table;
    const World world(scene, table);
    std::string all;
    for (const std::string& p : GeneratedSceneProblems(scene, world, 0.4, 0.4)) all += p + "; ";
    return all;
  };
  const double height = doc["room"]["size_m"][2];
  const double width = doc["room"]["size_m"][1];
  EXPECT_EQ(problems_with({{"asset", "shelf"}, {"position_m", {0.0, 1.0, 1.4}}, {"yaw_deg", 0}}), "");
  EXPECT_NE(problems_with({{"asset", "shelf"}, {"position_m", {0.1, 1.0, 1.4}}, {"yaw_deg", 0}})
                .find("(shelf) is wall-mounted but its back is not on a wall"),
            std::string::npos);
  EXPECT_NE(problems_with({{"asset", "shelf"}, {"position_m", {0.0, 1.0, 1.4}}, {"yaw_deg", 180}})
                .find("reaches outside the room"),
            std::string::npos);
  EXPECT_EQ(problems_with({{"asset", "shelf"}, {"position_m", {1.0, width, 1.4}}, {"yaw_deg", -90}}), "");
  EXPECT_EQ(problems_with({{"asset", "ceiling_light"}, {"position_m", {2.0, 2.0, height}}}), "");
  EXPECT_NE(problems_with({{"asset", "ceiling_light"}, {"position_m", {2.0, 2.0, height - 0.2}}})
                .find("(ceiling_light) does not touch the ceiling"),
            std::string::npos);
}

// A generated classroom with only its wall fittings at room temperature (and, when `lights`, its
// ceiling lights) left, its room surfaces and the environment at 22 °C (so that what the specular
// whiteboard mirrors reads 22 °C too) and no window, and a route heading straight at its front
// wall from 3.5 m; `pitch_deg` tilts the camera.
nlohmann::ordered_json ClearedClassroom(double pitch_deg, bool lights) {
  GeneratorOptions options;
  options.objects.whiteboard_probability = 1;
  nlohmann::ordered_json doc = GenerateScene("classroom", 5, 0, options);
  const double middle = 0.5 * doc["room"]["size_m"][1].get<double>();
  nlohmann::ordered_json kept = nlohmann::ordered_json::array();
  for (const auto& o : doc["objects"])
    for (const char* fitting : {"whiteboard", "door_frame", "light_switch", "wall_socket", "shelf"})
      if (o["asset"] == fitting || (lights && o["asset"] == "ceiling_light")) kept.push_back(o);
  doc["objects"] = kept;
  doc["tables"] = nlohmann::ordered_json::array();
  doc["crowd"]["seating"] = nlohmann::ordered_json::array();
  doc["crowd"]["standing"] = nlohmann::ordered_json::array();
  doc["crowd"]["walkers"] = 0;
  doc["room"]["windows"] = nlohmann::ordered_json::array();
  doc["room"]["environment_temperature_c"] = 22;
  doc["room"]["floor"] = {{"temperature_c", 22}};
  doc["room"]["ceiling"] = {{"temperature_c", 22}};
  doc["room"]["walls"] = {{"temperature_bottom_c", 22}, {"temperature_top_c", 22}};
  // The board mirrors the room: every surface exactly 22 °C (no texture, edges, plume or HVAC cycle).
  doc["room"]["surfaces"] = {{"texture", false}, {"thermal_bridges", false}, {"radiator_plume", false}};
  doc["room"]["hvac"] = {{"enabled", false}};
  doc["room"]["thermal"] = {{"enabled", false}};  // the declared temperatures, not the solution's
  doc["robot"] = {{"camera_pitch_deg", pitch_deg}};
  doc["route"]["waypoints_m"] = {{3.5, middle}, {1.2, middle}, {1.2, middle + 1.5}, {3.5, middle + 1.5}};
  return doc;
}

// The T_true of the pixels of `class_name` in the second frame of the scene's render.
std::vector<float> TrueTemperaturesOf(const nlohmann::ordered_json& doc, const std::string& class_name) {
  const test::TestDir dir(class_name);
  SequenceOptions render;
  render.output_dir = (dir.path() / "dataset").string();
  render.frames = 2;
  render.threads = 1;
  RenderSequence(Load(doc), render);
  const Dataset dataset = Dataset::Open(render.output_dir);
  const ExrChannels exr = ReadDatasetExr(dataset, 1);
  const std::string path = DatasetExrPath(dataset, 1);
  const cv::Mat& cls = ExrChannel(exr, "class", path);
  const cv::Mat& t_true = ExrChannel(exr, "T_true", path);
  std::vector<float> out;
  for (int y = 0; y < cls.rows; ++y)
    for (int x = 0; x < cls.cols; ++x)
      if (static_cast<int>(cls.at<float>(y, x)) == dataset.manifest().ClassId(class_name))
        out.push_back(t_true.at<float>(y, x));
  return out;
}

// The rendered frame's ground truth (T_true, before sensor noise) shows a generated room's
// whiteboard at its documented 22 °C (board and frame; the lights are taken out for this view, as
// the board would mirror them) and its ceiling lights' diffuser (26 °C,
// ε 0.94) and frame (30 °C, ε 0.93) at the band radiance ε·B(T) + (1 − ε)·B(22 °C) gives.
TEST(Generator, AGeneratedRoomsWhiteboardAndCeilingLightsRenderAtTheirDocumentedTemperatures) {
  const std::vector<float> board = TrueTemperaturesOf(ClearedClassroom(8, false), "whiteboard");
  EXPECT_GT(board.size(), 256u * 192u / 10) << "the whiteboard fills a good part of the view";
  for (float t : board) ASSERT_NEAR(t, 22.0f, 0.01f);
  const std::vector<float> light = TrueTemperaturesOf(ClearedClassroom(-60, true), "ceiling_light");
  ASSERT_GT(light.size(), 100u) << "a ceiling light is in view";
  const BandRadianceTable band;
  auto apparent = [&](float t_c, float emissivity) {
    return band.CelsiusFromRadiance(emissivity * band.RadianceFromCelsius(t_c) +
                                    (1 - emissivity) * band.RadianceFromCelsius(22));
  };
  const float diffuser = apparent(26, 0.94f), frame = apparent(30, 0.93f);
  int diffuser_pixels = 0, frame_pixels = 0;
  for (float t : light) {
    diffuser_pixels += std::abs(t - diffuser) < 0.02f;
    frame_pixels += std::abs(t - frame) < 0.02f;
  }
  EXPECT_GT(diffuser_pixels, frame_pixels);
  EXPECT_GT(frame_pixels, 0);
  EXPECT_GE(diffuser_pixels + frame_pixels, static_cast<int>(light.size() * 9 / 10)) << "edge pixels mix the two";
}

TEST(Generator, ABadLayoutNameIsRefusedNamingTheFamilies) {
  try {
    FamilyOf("kitchen", 1, 0);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--layout"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("one of: meeting_row, classroom"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'kitchen'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace hoilcd
