// A building floor's world: interior walls are solid to rays and to the robot, and a floor
// renders the same bytes at one and two threads.
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "hoilcd/sim/output/sequence.h"
#include "hoilcd/sim/world/world.h"
#include "test_dir.h"
#include "two_room_floor.h"

namespace hoilcd {
namespace {

using nlohmann::json;

TEST(FloorWorld, InteriorWallOccludesAndItsDoorwayDoesNot) {
  const Scene scene = SceneFromJson(test::TwoRoomFloor(), "floor.json");
  const BandRadianceTable table;
  const World world(scene, table);
  // From the west room eastwards at y = 2.5 (between the doorways): the wall's west face at x = 4.0.
  const RayHit wall = world.caster().Intersect({1.0f, 2.5f, 1.0f}, {1.0f, 0.0f, 0.0f});
  ASSERT_GE(wall.instance, 0);
  EXPECT_NEAR(wall.distance_m, 3.0f, 1e-4f);
  EXPECT_EQ(world.instance(wall.instance).class_id, world.classes().at("wall"));
  // Through the doorway at y = 1.5: the floor's east outer wall at x = 8.12.
  const RayHit through = world.caster().Intersect({1.0f, 1.5f, 1.0f}, {1.0f, 0.0f, 0.0f});
  EXPECT_NEAR(through.distance_m, 7.12f, 1e-4f);
  // Above the doorway (z 2.1-2.8) the lintel stops the ray.
  const RayHit lintel = world.caster().Intersect({1.0f, 1.5f, 2.5f}, {1.0f, 0.0f, 0.0f});
  EXPECT_NEAR(lintel.distance_m, 3.0f, 1e-4f);
}

TEST(FloorWorld, InteriorWallsAreFootprintsTheRobotAvoids) {
  const Scene scene = SceneFromJson(test::TwoRoomFloor(), "floor.json");
  const BandRadianceTable table;
  const World world(scene, table);
  int walls = 0;
  for (const Obstacle2D& o : world.obstacles()) walls += o.name.rfind("interior wall 0.", 0) == 0 ? 1 : 0;
  EXPECT_EQ(walls, 3);
  RouteOptions route = scene.route;
  route.frames = 0;  // a whole lap, through both doorways
  route.laps = 1;
  const RobotRun run =
      SimulateRobot(scene.robot, route, scene.odometry, world.obstacles(), scene.frame_rate_hz, scene.seed);
  EXPECT_GT(run.min_obstacle_distance_m, 0.2);
  EXPECT_GE(run.laps, 1.0);
}

std::string Bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(FloorWorld, ShippedFloorRendersTheSameBytesAtOneAndTwoThreads) {
  const Scene scene = LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/office_floor.json");
  test::TestDir dir;
  for (int threads : {1, 2}) {
    SequenceOptions options;
    options.output_dir = (dir.path() / std::to_string(threads)).string();
    options.frames = 3;
    options.threads = threads;
    options.outputs = "thermal,radiometric";
    RenderSequence(scene, options);
  }
  int compared = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir.path() / "1")) {
    if (!entry.is_regular_file() || entry.path().extension() != ".png") continue;
    const std::filesystem::path other = dir.path() / "2" / std::filesystem::relative(entry.path(), dir.path() / "1");
    EXPECT_EQ(Bytes(entry.path()), Bytes(other)) << entry.path();
    ++compared;
  }
  EXPECT_GE(compared, 3);
}

}  // namespace
}  // namespace hoilcd
