// hoilcd generate's scenes: every layout family gives valid, collision-free scenes over 50 seeds
// (footprints inside the room and apart, seats reachable, the route a closed loop keeping its
// clearance, the robot's run clear of every footprint), the same bytes on every run, and what
// `mixed` draws is what the family alone gives.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <set>

#include "hoilcd/core/util/parallel.h"
#include "hoilcd/sim/generate/generator.h"
#include "hoilcd/sim/output/sequence.h"
#include "hoilcd/sim/scene/scene_options.h"

namespace hoilcd {
namespace {

constexpr int kSeeds = 50;

Scene Load(const nlohmann::ordered_json& doc) { return SceneFromJson(nlohmann::json::parse(doc.dump()), "generated.json"); }

class EveryLayout : public testing::TestWithParam<std::string> {};

TEST_P(EveryLayout, GivesValidCollisionFreeScenesWithReachableSeatsAndAClearClosedRouteOver50Seeds) {
  const GeneratorOptions options;
  std::vector<std::string> failures(kSeeds);
  ParallelFor(kSeeds, 0, [&](int64_t seed) {
    try {
      const nlohmann::ordered_json doc = GenerateScene(GetParam(), static_cast<uint64_t>(seed), 0, options);
      const Scene scene = Load(doc);
      const BandRadianceTable table;
      const World world(scene, table);
      std::string problems;
      for (const std::string& p : GeneratedSceneProblems(scene, world, options.route_wall_m, options.route_clearance_m)) problems += p + "; ";
      const RobotRun run = SimulateSceneRobot(scene, world.obstacles());
      if (run.laps < options.laps - 0.01) problems += "the robot drove only " + std::to_string(run.laps) + " laps; ";
      if (scene.tables.empty() && scene.crowd.standing.empty()) problems += "an empty room; ";
      if (doc["generator"]["layout"] != GetParam()) problems += "generator.layout is not the family; ";
      if (!problems.empty()) failures[static_cast<size_t>(seed)] = "seed " + std::to_string(seed) + ": " + problems;
    } catch (const std::exception& e) {
      failures[static_cast<size_t>(seed)] = "seed " + std::to_string(seed) + ": " + e.what();
    }
  });
  for (const std::string& f : failures) EXPECT_EQ(f, "");
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
  EXPECT_NE(SceneFileText(GenerateScene("classroom", 11, 0, options)), SceneFileText(GenerateScene("classroom", 12, 0, options)));
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
