#include "hoilcd/sim/scene/building_floor.h"

#include <deque>
#include <string>

#include <gtest/gtest.h>

#include "hoilcd/sim/scene/scene.h"
#include "input_error_of.h"
#include "two_room_floor.h"

namespace hoilcd {
namespace {

using nlohmann::json;
using test::InputErrorOf;
using test::TwoRoomFloor;

std::string ShippedFloor() { return std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/office_floor.json"; }

// Rooms reached from room 0 through the room graph.
int Reached(const FloorPlan& floor, double height_m) {
  const std::vector<std::vector<int>> graph = RoomGraph(floor, height_m);
  std::vector<bool> seen(floor.rooms.size(), false);
  std::deque<int> queue = {0};
  seen[0] = true;
  int count = 1;
  while (!queue.empty()) {
    const int r = queue.front();
    queue.pop_front();
    for (int n : graph[r])
      if (!seen[n]) seen[n] = true, ++count, queue.push_back(n);
  }
  return count;
}

TEST(BuildingFloor, ShippedFloorLoadsWithAtLeastEightRoomsApartAndAllReachable) {
  const Scene scene = LoadScene(ShippedFloor());
  int rooms = 0;
  for (const FloorRoom& r : scene.floor.rooms) rooms += r.corridor ? 0 : 1;
  EXPECT_GE(rooms, 8);
  for (size_t i = 0; i < scene.floor.rooms.size(); ++i) {
    for (size_t j = i + 1; j < scene.floor.rooms.size(); ++j) {
      const Eigen::AlignedBox2d overlap = scene.floor.rooms[i].box_m.intersection(scene.floor.rooms[j].box_m);
      EXPECT_TRUE(overlap.isEmpty() || overlap.sizes().minCoeff() < 1e-3)
          << scene.floor.rooms[i].name << " / " << scene.floor.rooms[j].name;
    }
  }
  EXPECT_EQ(Reached(scene.floor, scene.room.size_m.z()), static_cast<int>(scene.floor.rooms.size()));
}

TEST(BuildingFloor, SceneWithoutFloorHasAnEmptyPlanAndAnUnchangedResolvedDocument) {
  const Scene scene = SceneFromJson(json::object(), "empty.json");
  EXPECT_TRUE(scene.floor.empty());
  EXPECT_FALSE(scene.resolved.contains("floor"));
}

TEST(BuildingFloor, WallPartsLeaveTheDoorwaysOpenWithLintelsAbove) {
  const Scene scene = SceneFromJson(TwoRoomFloor(), "floor.json");
  const std::vector<WallPart> parts = WallParts(scene.floor, 2.8);
  int full = 0, lintels = 0;
  for (const WallPart& p : parts) {
    (p.lintel ? lintels : full) += 1;
    EXPECT_NEAR(p.box_m.min().x(), 4.0, 1e-9);
    EXPECT_NEAR(p.box_m.max().x(), 4.12, 1e-9);
    if (p.lintel) {
      EXPECT_NEAR(p.box_m.min().z(), 2.1, 1e-9);
    }
  }
  EXPECT_EQ(full, 3);  // y 0-0.9, 2.1-2.9, 4.1-5
  EXPECT_EQ(lintels, 2);
  EXPECT_EQ(Reached(scene.floor, 2.8), 2);
}

TEST(BuildingFloor, OverlappingRoomsNameTheRoom) {
  json doc = TwoRoomFloor();
  doc["floor"]["rooms"][1]["min_m"] = {3.5, 0.0};
  const std::string error = InputErrorOf([&] { SceneFromJson(doc, "floor.json"); });
  EXPECT_NE(error.find("floor.json: /floor/rooms/1: a room apart from the others; 'east' overlaps room 0 'west'"),
            std::string::npos)
      << error;
}

TEST(BuildingFloor, DoorwayBeyondItsWallNamesTheDoor) {
  json doc = TwoRoomFloor();
  doc["floor"]["walls"][0]["doors"][1]["center_m"] = 5.8;
  const std::string error = InputErrorOf([&] { SceneFromJson(doc, "floor.json"); });
  EXPECT_NE(error.find("floor.json: /floor/walls/0/doors/1/center_m: a doorway within its wall: the wall is 5 m long"),
            std::string::npos)
      << error;
}

TEST(BuildingFloor, RouteThroughAWallNamesTheLeg) {
  json doc = TwoRoomFloor();
  doc["route"]["waypoints_m"] = {{1.0, 1.5}, {1.0, 2.5}, {7.1, 2.5}, {7.1, 1.5}};
  const std::string error = InputErrorOf([&] { SceneFromJson(doc, "floor.json"); });
  EXPECT_NE(error.find("floor.json: /route/waypoints_m/1: a leg clear of the interior walls"), std::string::npos)
      << error;
  EXPECT_NE(error.find("passes through /floor/walls/0 outside its doorways"), std::string::npos) << error;
}

TEST(BuildingFloor, SlantedWallNamesItsEnd) {
  json doc = TwoRoomFloor();
  doc["floor"]["walls"][0]["to_m"] = {4.5, 5.0};
  const std::string error = InputErrorOf([&] { SceneFromJson(doc, "floor.json"); });
  EXPECT_NE(error.find("floor.json: /floor/walls/0/to_m: a point at least 1 cm from from_m"), std::string::npos)
      << error;
}

TEST(BuildingFloor, RoomWithoutADoorwayIsUnreachable) {
  json doc = TwoRoomFloor();
  doc["floor"]["walls"][0]["doors"] = json::array();
  doc["route"]["waypoints_m"] = {{1.0, 1.0}, {1.0, 3.5}, {3.0, 3.5}, {3.0, 1.0}};
  const std::string error = InputErrorOf([&] { SceneFromJson(doc, "floor.json"); });
  EXPECT_NE(
      error.find("floor.json: /floor/rooms/1: a room reachable from room 0 'west' through doorways; 'east' is not"),
      std::string::npos)
      << error;
}

TEST(BuildingFloor, RoomOutsideTheBoxAndUnknownKeysAreRefused) {
  json doc = TwoRoomFloor();
  doc["floor"]["rooms"][1]["max_m"] = {9.0, 5.0};
  std::string error = InputErrorOf([&] { SceneFromJson(doc, "floor.json"); });
  EXPECT_NE(error.find("floor.json: /floor/rooms/1: a room inside the room box"), std::string::npos) << error;
  doc = TwoRoomFloor();
  doc["floor"]["walls"][0]["thicknes_m"] = 0.1;
  error = InputErrorOf([&] { SceneFromJson(doc, "floor.json"); });
  EXPECT_NE(error.find("/floor/walls/0: unknown key 'thicknes_m'"), std::string::npos) << error;
}

}  // namespace
}  // namespace hoilcd
