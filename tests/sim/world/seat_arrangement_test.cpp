// Tables seat people as their `seats` says (both long sides, one side, around, on a sofa, none),
// each with its own asset; a scene that names a seat its table lacks, or a missing asset, is
// refused at the JSON pointer.
#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hoilcd/sim/world/world.h"
#include "input_error_of.h"

namespace hoilcd {
namespace {

using nlohmann::json;

json Room() {
  return {
      {"name", "seats"},
      {"frames", 50},
      {"room", {{"size_m", {9.0, 6.0, 2.6}}}},
      {"objects", json::array()},
      {"tables",
       {{{"center_m", {1.5, 3.0}}},
        {{"center_m", {3.2, 3.0}}, {"asset", "desk"}, {"seats", "one_side"}, {"yaw_deg", 90}},
        {{"center_m", {5.0, 3.0}}, {"asset", "round_table"}, {"seats", "around"}, {"seat_count", 6}},
        {{"center_m", {7.0, 2.0}}, {"asset", "sofa"}, {"seats", "sofa"}, {"yaw_deg", 90}},
        {{"center_m", {7.0, 3.0}}, {"asset", "low_table"}, {"seats", "none"}}}},
      {"crowd", {{"seating", {{{"table", 0}, {"seat", 4}}, {{"table", 2}, {"seat", 5}}, {{"table", 3}, {"seat", 2}}}}}},
      {"route", {{"waypoints_m", {{0.4, 0.4}, {0.4, 5.6}, {8.6, 5.6}, {8.6, 0.4}}}}}};
}

Eigen::Vector2d Facing(const Crowd::SeatPlace& s) {
  return s.world_from_seat.block<2, 1>(0, 0).cast<double>().normalized();
}
Eigen::Vector2d At(const Crowd::SeatPlace& s) { return s.world_from_seat.topRightCorner<2, 1>().cast<double>(); }

TEST(SeatArrangement, EveryTableSeatsPeopleAsItsSeatsSays) {
  const Scene scene = SceneFromJson(Room(), "seats.json");
  const BandRadianceTable table;
  const World world(scene, table);
  std::map<int, std::vector<Crowd::SeatPlace>> by_table;
  for (const Crowd::SeatPlace& s : world.seat_places()) by_table[s.table].push_back(s);
  EXPECT_EQ(by_table[0].size(), 4u);  // both sides, people_per_table 4: two a side
  ASSERT_EQ(by_table[1].size(), 2u);  // a desk, two seats on its -y side, turned 90°: facing -x
  for (const Crowd::SeatPlace& s : by_table[1]) {
    EXPECT_GT(At(s).x(), 3.2 + 0.3);
    EXPECT_LT(Facing(s).x(), -0.95);
    EXPECT_TRUE(s.chair);
  }
  ASSERT_EQ(by_table[2].size(), 6u);  // round: six, facing the centre, the first on -y
  for (const Crowd::SeatPlace& s : by_table[2]) {
    const Eigen::Vector2d to_centre = (Eigen::Vector2d(5.0, 3.0) - At(s)).normalized();
    EXPECT_GT(Facing(s).dot(to_centre), 0.93);
    EXPECT_NEAR((At(s) - Eigen::Vector2d(5.0, 3.0)).norm(), 0.45 + 0.15, 0.08);
  }
  EXPECT_LT(At(by_table[2][0]).y(), 3.0 - 0.5);
  ASSERT_EQ(by_table[3].size(), 3u);  // a sofa: three places, no chairs, facing +x turned 90°: +y
  for (const Crowd::SeatPlace& s : by_table[3]) {
    EXPECT_FALSE(s.chair);
    EXPECT_GT(Facing(s).y(), 0.99);
  }
  EXPECT_EQ(by_table.count(4), 0u);  // the low table seats nobody
  int seated = 0, chairs = 0;
  for (const Person& p : world.people()) seated += p.seated;
  for (const Obstacle2D& o : world.obstacles()) chairs += o.name.rfind("chair ", 0) == 0;
  EXPECT_EQ(seated, 3);
  EXPECT_EQ(chairs, 4 + 2 + 6);
  // Nobody on a sofa has a cup or a laptop: there is no table top.
  for (const Person& p : world.people()) {
    if (p.table != 3) continue;
    EXPECT_TRUE(p.cup < 0 && p.laptop < 0 && !p.at_table_top);
  }
}

TEST(SeatArrangement, ASeatItsTableLacksAndAMissingAssetAreRefusedAtTheirPointers) {
  json doc = Room();
  doc["crowd"]["seating"][1]["seat"] = 6;
  doc["tables"][1]["asset"] = "no_such_desk";
  const std::string message = test::InputErrorOf([&] { SceneFromJson(doc, "seats.json"); });
  EXPECT_NE(message.find("seats.json: /crowd/seating/1/seat"), std::string::npos) << message;
  EXPECT_NE(message.find("a seat table 2 has (0..5)"), std::string::npos) << message;
  EXPECT_NE(message.find("seats.json: /tables/1/asset"), std::string::npos) << message;
}

}  // namespace
}  // namespace hoilcd
