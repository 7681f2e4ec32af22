// A small building floor for tests: two empty 4 x 5 m rooms side by side, a 0.12 m wall between
// them at x = 4.06 with two 1.2 m doorways (y 0.9-2.1 and 2.9-4.1), and a clockwise route through
// both doorways.
#pragma once

#include <nlohmann/json.hpp>

namespace hoilcd::test {

inline nlohmann::json TwoRoomFloor() {
  using nlohmann::json;
  return {{"tables", json::array()},
          {"objects", json::array()},
          {"frames", 50},
          {"room", {{"size_m", {8.12, 5.0, 2.8}}, {"sun", {{"enabled", false}}}}},
          {"crowd", {{"walkers", 0}}},
          {"floor",
           {{"rooms",
             {{{"name", "west"}, {"min_m", {0.0, 0.0}}, {"max_m", {4.0, 5.0}}},
              {{"name", "east"}, {"min_m", {4.12, 0.0}}, {"max_m", {8.12, 5.0}}}}},
            {"walls",
             {{{"from_m", {4.06, 0.0}},
               {"to_m", {4.06, 5.0}},
               {"thickness_m", 0.12},
               {"doors", {{{"center_m", 1.5}, {"width_m", 1.2}}, {{"center_m", 3.5}, {"width_m", 1.2}}}}}}}}},
          {"route", {{"waypoints_m", {{1.0, 1.5}, {1.0, 3.5}, {7.1, 3.5}, {7.1, 1.5}}}}}};
}

}  // namespace hoilcd::test
