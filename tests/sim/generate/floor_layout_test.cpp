// The building floor of `hoilcd generate --layout floor`: the shipped floor's route and a freshly
// generated small floor.
#include <gtest/gtest.h>

#include "hoilcd/sim/generate/generator.h"
#include "hoilcd/sim/robot/robot.h"

namespace hoilcd {
namespace {

Scene ShippedFloor() { return LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/office_floor.json"); }

double TwiceSignedArea(const std::vector<Eigen::Vector2d>& route) {
  double area = 0;
  for (size_t i = 0; i < route.size(); ++i) {
    const Eigen::Vector2d& a = route[i];
    const Eigen::Vector2d& b = route[(i + 1) % route.size()];
    area += a.x() * b.y() - b.x() * a.y();
  }
  return area;
}

TEST(FloorLayout, ShippedRouteIsAClockwiseLoopThroughDoorwaysIntoEveryRoom) {
  const Scene scene = ShippedFloor();
  const std::vector<Eigen::Vector2d>& route = scene.route.waypoints_m;
  EXPECT_LT(TwiceSignedArea(route), 0.0);
  int rooms = 0;
  for (const FloorRoom& room : scene.floor.rooms) {
    if (room.corridor) continue;
    ++rooms;
    EXPECT_TRUE(std::any_of(route.begin(), route.end(), [&](const Eigen::Vector2d& p) {
      return room.box_m.contains(p);
    })) << room.name;
  }
  // Every leg keeps 0.4 m from the interior walls, so where it crosses a wall's line it is in a doorway:
  // each room is entered and left through its two doorways on the corridor's walls.
  int crossings = 0;
  for (size_t i = 0; i < route.size(); ++i) {
    const Eigen::Vector2d& a = route[i];
    const Eigen::Vector2d& b = route[(i + 1) % route.size()];
    EXPECT_EQ(WallCrossedBy(scene.floor, a, b, 0.4, scene.room.size_m.z()), -1) << "leg " << i;
    for (size_t w = 0; w < 2; ++w) {  // the two corridor walls
      const double y = scene.floor.walls[w == 0 ? 0 : scene.floor.walls.size() / 2].from_m.y();
      if ((a.y() - y) * (b.y() - y) < 0) ++crossings;
    }
  }
  EXPECT_EQ(crossings, 2 * rooms);
}

TEST(FloorLayout, ShippedFloorPassesTheGeneratorsChecksAndItsRobotDrivesALapClear) {
  const Scene scene = ShippedFloor();
  const BandRadianceTable table;
  const World world(scene, table);
  const GeneratorOptions options;
  const std::vector<std::string> problems = GeneratedSceneProblems(
      scene, world, options.route_wall_m, options.route_clearance_m - scene.furniture.chair_jitter_m);
  EXPECT_TRUE(problems.empty()) << problems.front();
  RouteOptions route = scene.route;
  route.frames = scene.frames / 2;
  const RobotRun run =
      SimulateRobot(scene.robot, route, scene.odometry, world.obstacles(), scene.frame_rate_hz, scene.seed);
  EXPECT_GT(run.min_obstacle_distance_m, 0.1) << run.closest_obstacle;
  EXPECT_GT(run.laps, 0.9);
}

TEST(FloorLayout, SmallFloorIsGeneratedTheSameTwiceAndLoads) {
  GeneratorOptions options;
  options.floor.rooms_per_side = 1;
  options.laps = 1;
  const nlohmann::ordered_json a = GenerateScene("floor", 5, 0, options);
  EXPECT_EQ(SceneFileText(a), SceneFileText(GenerateScene("floor", 5, 0, options)));
  const Scene scene = SceneFromJson(nlohmann::json::parse(a.dump()), "small_floor.json");
  int rooms = 0;
  for (const FloorRoom& room : scene.floor.rooms) rooms += room.corridor ? 0 : 1;
  EXPECT_EQ(rooms, 2);
  EXPECT_EQ(a["generator"]["layout"], "floor");
  EXPECT_EQ(FamilyOf("floor", 5, 0), "floor");
}

}  // namespace
}  // namespace hoilcd
