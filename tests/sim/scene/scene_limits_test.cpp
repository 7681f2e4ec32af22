// What a scene file may not do however it is written (issue 45): nest without bound, repeat a
// key, list without bound, give a frame rate that makes a run endless, hide a '=' in a run's
// override key, or give an integer that a double would round into its range.
#include <algorithm>
#include <chrono>
#include <fstream>
#include <functional>

#include <gtest/gtest.h>

#include "cpu_seconds.h"
#include "hoilcd/core/util/json_reader.h"
#include "hoilcd/core/util/sizes.h"
#include "hoilcd/sim/scene/scene.h"
#include "input_error_of.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

using nlohmann::json;
using test::InputErrorOf;

// CPU seconds, not wall time: a loaded machine must not fail a bound on a step's cost.
double SecondsOf(const std::function<void()>& fn) { return test::CpuSecondsOf(fn); }

std::string WriteScene(const test::TestDir& dir, const std::string& text) {
  const std::string path = dir / "scene.json";
  std::ofstream(path) << text;
  return path;
}

std::string LoadError(const std::string& path, const std::vector<std::string>& overrides = {}) {
  return InputErrorOf([&] { LoadScene(path, overrides); });
}

std::string ErrorOf(const json& doc, const std::vector<std::string>& overrides = {}) {
  return InputErrorOf([&] { SceneFromJson(doc, "test.json", overrides); });
}

std::string Nested(const std::string& open, const std::string& inner, const std::string& close, int depth) {
  std::string text;
  for (int i = 0; i < depth; ++i) text += open;
  text += inner;
  for (int i = 0; i < depth; ++i) text += close;
  return text;
}

TEST(SceneLimits, NestingAHundredThousandDeepAnywhereIsRefusedWithinTwoSeconds) {
  const test::TestDir dir;
  const std::string deep_array = Nested("[", "", "]", 100000), deep_object = Nested(R"({"a":)", "1", "}", 100000);
  for (const std::string& text :
       {deep_object, R"({"description": )" + deep_array + "}",
        R"({"runs": [{"time_of_day_h": 9}, {"time_of_day_h": 12, "set": {"description": )" + deep_array + "}}]}"}) {
    std::string error;
    EXPECT_LT(SecondsOf([&] { error = LoadError(WriteScene(dir, text)); }), 2.0);
    EXPECT_NE(error.find("nests deeper than 64 levels"), std::string::npos) << error.substr(0, 300);
  }
  std::string error;
  EXPECT_LT(SecondsOf([&] { error = ErrorOf(json::object(), {"description=" + deep_array}); }), 2.0);
  EXPECT_NE(error.find("--set description=[[[["), std::string::npos) << error.substr(0, 100);
  EXPECT_NE(error.find("nests deeper than 64 levels"), std::string::npos) << error.substr(0, 300);
}

TEST(SceneLimits, ARepeatedKeyIsRefusedAtItsPointer) {
  const test::TestDir dir;
  std::string error = LoadError(WriteScene(dir, R"({"frames": 40, "frames": 30})"));
  EXPECT_NE(error.find(R"(scene.json: /frames: the key "frames" is repeated)"), std::string::npos) << error;
  error = LoadError(WriteScene(dir, R"({"runs": [{"time_of_day_h": 9}, {"time_of_day_h": 12, "time_of_day_h": 13}]})"));
  EXPECT_NE(error.find("scene.json: /runs/1/time_of_day_h: "), std::string::npos) << error;
  error = ErrorOf(json::object(), {R"(crowd={"people_per_table": 1, "people_per_table": 2})"});
  EXPECT_NE(error.find("/people_per_table: the key \"people_per_table\" is repeated"), std::string::npos) << error;
}

TEST(SceneLimits, AFolderIsNamedAsOne) {
  const test::TestDir dir;
  EXPECT_NE(LoadError(dir.str()).find(dir.str() + ": is a folder: expected a regular file"), std::string::npos)
      << LoadError(dir.str());
}

TEST(SceneLimits, AFrameRateBelowOneHertzIsRefusedBeforeAnythingIsDerivedFromIt) {
  for (const char* rate : {"1e-300", "0.001", "0.999"}) {
    std::string error;
    EXPECT_LT(SecondsOf([&] { error = ErrorOf(json::object(), {std::string("frame_rate_hz=") + rate}); }), 2.0);
    EXPECT_NE(error.find("test.json: /frame_rate_hz"), std::string::npos) << rate << ": " << error;
  }
  EXPECT_EQ(ErrorOf(json::object(), {"frame_rate_hz=1"}), "");
}

TEST(SceneLimits, ARunsOverrideKeyHoldingAnEqualsSignIsRefused) {
  for (const char* key : {"name=another", "assets_dir=/x", "crowd.people_per_table=3"}) {
    const json doc = {{"frames", 10},
                      {"runs", json::array({{{"time_of_day_h", 9}}, {{"time_of_day_h", 12}, {"set", {{key, 1}}}}})}};
    const std::string error = ErrorOf(doc);
    EXPECT_NE(error.find("test.json: /runs/1/set/" + JsonPointerToken(key) + ": a scene path, which never holds '='"),
              std::string::npos)
        << key << ": " << error;
  }
}

TEST(SceneLimits, ASeedAboveTwoToThe53IsRefusedThoughADoubleWouldRoundItIntoRange) {
  const std::string above = "9007199254740993";  // 2^53 + 1: as a double, 2^53
  EXPECT_NE(
      ErrorOf(json::parse(R"({"seed": )" + above + "}")).find("test.json: /seed: expected at most 9007199254740992"),
      std::string::npos);
  EXPECT_NE(ErrorOf(json::object(), {"seed=" + above}).find("test.json: /seed: expected at most"), std::string::npos);
  const json runs =
      json::parse(R"({"frames": 10, "runs": [{"time_of_day_h": 9}, {"time_of_day_h": 12, "seed": )" + above + "}]}");
  EXPECT_NE(ErrorOf(runs).find("test.json: /runs/1/seed: expected at most 9007199254740992"), std::string::npos)
      << ErrorOf(runs);
  EXPECT_EQ(SceneFromJson(json{{"seed", kMaxSeed}}, "test.json").seed, kMaxSeed);
}

// Every integer the schema bounds, given as the bound and one beyond it: the bound itself passes
// that check, one beyond is refused at its pointer, however large the bound.
void ForEachBoundedInteger(const json& schema, const std::string& path,
                           const std::function<void(const std::string&, const json&)>& fn) {
  if (schema.value("type", "") == "integer" && (schema.contains("maximum") || schema.contains("minimum")))
    fn(path, schema);
  if (schema.contains("properties")) {
    for (const auto& [key, sub] : schema["properties"].items()) {
      ForEachBoundedInteger(sub, path.empty() ? key : path + "." + key, fn);
    }
  }
}

TEST(SceneLimits, EveryBoundedIntegerIsComparedAsAnIntegerAtBothEdges) {
  int checked = 0;
  ForEachBoundedInteger(SceneSchema(), "", [&](const std::string& key, const json& schema) {
    std::string pointer = "/" + key;
    std::replace(pointer.begin(), pointer.end(), '.', '/');
    for (const char* edge : {"maximum", "minimum"}) {
      if (!schema.contains(edge)) continue;
      const bool max = std::string(edge) == "maximum";
      const json bound = schema[edge];
      // One beyond the bound, as text: 2^53 + 1 is exactly what a double cannot hold.
      const std::string beyond = bound.is_number_unsigned() && max
                                     ? std::to_string(bound.get<uint64_t>() + 1)
                                     : std::to_string(bound.get<int64_t>() + (max ? 1 : -1));
      const std::string error = ErrorOf(json::object(), {key + "=" + beyond});
      EXPECT_NE(error.find("test.json: " + pointer + ": "), std::string::npos) << key << "=" << beyond << ": " << error;
      const std::string at_bound = ErrorOf(json::object(), {key + "=" + bound.dump()});
      EXPECT_EQ(at_bound.find("test.json: " + pointer + ": expected at"), std::string::npos) << key << ": " << at_bound;
      ++checked;
    }
  });
  EXPECT_GT(checked, 20);
}

// Every list in the schema has a longest length, and every object with keys of the user's choice a
// largest count of them: no count of items goes unbounded.
void ForEachList(const json& schema, const std::string& pointer,
                 const std::function<void(const std::string&, const json&)>& fn) {
  if (schema.value("type", "") == "array") fn(pointer, schema);
  if (schema.value("type", "") == "object" && !schema.contains("properties")) fn(pointer, schema);
  if (schema.contains("properties")) {
    for (const auto& [key, sub] : schema["properties"].items()) ForEachList(sub, pointer + "/" + key, fn);
  }
  if (schema.contains("items") && schema["items"].is_object()) ForEachList(schema["items"], pointer + "/0", fn);
}

TEST(SceneLimits, EveryListOfTheSchemaHasALongestLength) {
  int lists = 0;
  ForEachList(SceneSchema(), "", [&](const std::string& pointer, const json& schema) {
    EXPECT_TRUE(schema.contains(schema.value("type", "") == "array" ? "maxItems" : "maxProperties")) << pointer;
    ++lists;
  });
  EXPECT_GT(lists, 15);
}

TEST(SceneLimits, AHundredThousandItemsInAnyListAreRefusedWithinTwoSeconds) {
  const json table = {{"center_m", {2.0, 1.5}}};
  const json item_of[] = {table,
                          json{{"asset", "cup"}, {"position_m", {1.0, 1.0, 0.7}}},
                          json{{"table", 0}, {"seat", 0}},
                          json{{"position_m", {1.0, 1.0}}},
                          json{{"wall", "north"}, {"center_m", 1.0}},
                          json{{"position_m", {0.0, 1.5}}, {"width_m", 0.9}},
                          json{1.0, 1.0},
                          json{{"time_of_day_h", 9}}};
  const char* const lists[] = {"/tables",       "/objects",    "/crowd/seating",     "/crowd/standing",
                               "/room/windows", "/room/doors", "/route/waypoints_m", "/runs"};
  for (size_t k = 0; k < std::size(lists); ++k) {
    json doc = json::object();
    doc[json::json_pointer(lists[k])] = json::array();
    json& list = doc[json::json_pointer(lists[k])];
    for (int i = 0; i < 100000; ++i) list.push_back(item_of[k]);
    std::string error;
    EXPECT_LT(SecondsOf([&] { error = ErrorOf(doc); }), 2.0) << lists[k];
    EXPECT_NE(error.find(std::string("test.json: ") + lists[k] + ": "), std::string::npos)
        << lists[k] << ": " << error.substr(0, 300);
  }
  json sets = json::object();
  for (int i = 0; i < 100000; ++i) sets["description" + std::to_string(i)] = 1;
  const json doc = {{"frames", 10},
                    {"runs", json::array({{{"time_of_day_h", 9}}, {{"time_of_day_h", 12}, {"set", sets}}})}};
  std::string error;
  EXPECT_LT(SecondsOf([&] { error = ErrorOf(doc); }), 2.0);
  EXPECT_NE(error.find("test.json: /runs/1/set: "), std::string::npos) << error.substr(0, 300);
}

TEST(SceneLimits, RunsThatOverlapWithinAMinuteAreReportedToTheSecond) {
  const json doc = {
      {"frames", 10}, {"frame_rate_hz", 10}, {"runs", json::array({{{"time_of_day_h", 9}}, {{"time_of_day_h", 9.0}}})}};
  const std::string error = ErrorOf(doc);
  EXPECT_NE(error.find("run 1 starts at day 0 09:00:00, before run 0 ends at day 0 09:00:01"), std::string::npos)
      << error;
  const json half_second = {
      {"frames", 5}, {"frame_rate_hz", 10}, {"runs", json::array({{{"time_of_day_h", 9}}, {{"time_of_day_h", 9.0}}})}};
  EXPECT_NE(ErrorOf(half_second).find("run 1 starts at day 0 09:00:00.000, before run 0 ends at day 0 09:00:00.500"),
            std::string::npos)
      << ErrorOf(half_second);
  const json apart = {{"frames", 10000},
                      {"frame_rate_hz", 10},
                      {"runs", json::array({{{"time_of_day_h", 9}}, {{"time_of_day_h", 9.25}}})}};
  EXPECT_NE(ErrorOf(apart).find("run 1 starts at day 0 09:15, before run 0 ends at day 0 09:16"), std::string::npos)
      << ErrorOf(apart);
}

}  // namespace
}  // namespace hoilcd
