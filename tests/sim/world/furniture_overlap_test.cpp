// Furniture may touch but not stand in other furniture: tables stacked on one spot are refused
// naming both JSON paths (issue 45), found by a sweep that is the all-pairs test's equal.
#include <chrono>
#include <random>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cpu_seconds.h"
#include "hoilcd/sim/world/world.h"
#include "input_error_of.h"

namespace hoilcd {
namespace {

using nlohmann::json;

json TwoTables(const Eigen::Vector2d& second) {
  return {{"name", "tables"},
          {"frames", 50},
          {"room", {{"size_m", {7.0, 3.0, 2.6}}}},
          {"objects", json::array()},
          {"tables", {{{"center_m", {2.0, 1.5}}}, {{"center_m", {second.x(), second.y()}}}}},
          {"route", {{"waypoints_m", {{0.4, 0.4}, {0.4, 2.6}, {6.6, 2.6}, {6.6, 0.4}}}}}};
}

std::string WorldError(const json& doc) {
  return test::InputErrorOf([&] {
    const Scene scene = SceneFromJson(doc, "tables.json");
    const BandRadianceTable table;
    const World world(scene, table);
  });
}

TEST(FurnitureOverlap, TablesStackedOnOneSpotAreRefusedNamingBoth) {
  const std::string error = WorldError(TwoTables({2.0, 1.5}));
  EXPECT_NE(error.find("tables.json: /tables/1: stands in /tables/0 (centred at (2, 1.5))"), std::string::npos)
      << error;
  EXPECT_NE(WorldError(TwoTables({2.3, 1.6})).find("/tables/1: stands in /tables/0"), std::string::npos);
}

TEST(FurnitureOverlap, TablesPushedTogetherOrApartAreFine) {
  EXPECT_EQ(WorldError(TwoTables({2.9, 1.5})), "");  // the table is 0.9 m long: the two touch
  EXPECT_EQ(WorldError(TwoTables({3.2, 1.5})), "");
  EXPECT_EQ(WorldError(TwoTables({2.0, 2.3})), "");  // 0.75 m wide: side by side
}

TEST(FurnitureOverlap, TheSweepFindsThePairsEveryPairTestFinds) {
  std::mt19937 rng(45);
  std::uniform_real_distribution<double> x(0, 40), y(0, 20), size(0.05, 1.5), yaw(-M_PI, M_PI);
  std::vector<Obstacle2D> footprints;
  for (int i = 0; i < 3000; ++i) {
    footprints.push_back(i % 3 == 0 ? Obstacle2D::Circle("c", {x(rng), y(rng)}, 0.5 * size(rng))
                                    : Obstacle2D::Rectangle("r", {x(rng), y(rng)}, {size(rng), size(rng)}, yaw(rng)));
  }
  std::vector<std::pair<size_t, size_t>> all_pairs;
  for (size_t i = 0; i < footprints.size(); ++i) {
    for (size_t j = i + 1; j < footprints.size(); ++j) {
      if (FootprintsOverlap(footprints[i], footprints[j])) all_pairs.emplace_back(i, j);
    }
  }
  const double start = test::ProcessCpuSeconds();  // CPU time: a loaded machine stretches wall time
  EXPECT_EQ(OverlappingFootprints(footprints), all_pairs);
  EXPECT_LT(test::ProcessCpuSeconds() - start, 0.5);
  EXPECT_GT(all_pairs.size(), 100u);
}

}  // namespace
}  // namespace hoilcd
