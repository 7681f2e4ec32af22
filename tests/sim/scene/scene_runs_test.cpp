// Recording runs (/runs): each run's scene, times and seeds, and what a scene with runs refuses.
#include <gtest/gtest.h>

#include "hoilcd/sim/scene/scene.h"
#include "input_error_of.h"

namespace hoilcd {
namespace {

using nlohmann::json;

json TwoRuns() {
  return json{
      {"frames", 100},
      {"runs", json::array({{{"time_of_day_h", 9.0}},
                            {{"time_of_day_h", 14.5}, {"frames", 50}, {"set", {{"crowd.people_per_table", 2}}}}})}};
}

// Every problem the scene has, one a line ("" when it loads).
std::string ErrorOf(const json& doc, const std::vector<std::string>& overrides = {}) {
  return test::InputErrorOf([&] { SceneFromJson(doc, "test.json", overrides); });
}

TEST(SceneRuns, EachRunIsTheSceneAtItsTimeWithItsFramesSeedAndOverrides) {
  const Scene scene = SceneFromJson(TwoRuns(), "test.json");
  ASSERT_EQ(scene.runs.size(), 2u);
  EXPECT_EQ(scene.frames, 150);  // the runs' total
  EXPECT_EQ(scene.runs[0].start_time_s, 0);
  EXPECT_EQ(scene.runs[1].start_time_s, 5.5 * 3600);
  EXPECT_EQ(scene.runs[0].seed, scene.seed);  // the first run is the scene as it renders without runs
  EXPECT_NE(scene.runs[1].seed, scene.seed);

  const Scene first = SceneOfRun(scene, 0), second = SceneOfRun(scene, 1);
  EXPECT_TRUE(first.runs.empty());
  EXPECT_EQ(first.frames, 100);
  EXPECT_EQ(first.route.frames, 100);
  EXPECT_EQ(first.room.sun.time_of_day_h, 9.0);
  EXPECT_EQ(first.run_seed, scene.seed);
  EXPECT_EQ(first.clock_offset_s, 0);
  EXPECT_EQ(first.crowd.people_per_table, scene.crowd.people_per_table);
  EXPECT_EQ(second.frames, 50);
  EXPECT_EQ(second.room.sun.time_of_day_h, 14.5);
  EXPECT_EQ(second.run_seed, scene.runs[1].seed);
  EXPECT_EQ(second.seed, scene.seed);  // the building (walls, chairs, the camera's pattern) is the same
  EXPECT_EQ(second.clock_offset_s, 5.5 * 3600);
  EXPECT_EQ(second.crowd.people_per_table, 2);

  // The first run renders as the scene without runs at its time of day would.
  const Scene plain = SceneFromJson(json{{"frames", 100}, {"room", {{"sun", {{"time_of_day_h", 9.0}}}}}}, "test.json");
  EXPECT_EQ(first.resolved, plain.resolved);
}

TEST(SceneRuns, AScenesWithoutRunsIsItsOwnOnlyRun) {
  const Scene scene = SceneFromJson(json::object(), "test.json");
  EXPECT_TRUE(scene.runs.empty());
  EXPECT_EQ(scene.run_seed, scene.seed);
  EXPECT_EQ(SceneOfRun(scene, 0).resolved, scene.resolved);
  EXPECT_FALSE(scene.resolved.contains("runs"));  // no default: existing scenes keep their hash
}

TEST(SceneRuns, ALaterDayCountsTheSunsDayOnAndAGivenSeedIsKept) {
  json doc = TwoRuns();
  doc["runs"][1]["time_of_day_h"] = 8.0;
  doc["runs"][1]["day"] = 2;
  doc["runs"][1]["seed"] = 77;
  doc["room"]["sun"]["day_of_year"] = 364;
  const Scene scene = SceneFromJson(doc, "test.json");
  EXPECT_EQ(scene.runs[1].start_time_s, (48 - 1) * 3600.0);
  const Scene second = SceneOfRun(scene, 1);
  EXPECT_EQ(second.room.sun.day_of_year, 1);  // 364 + 2 wraps into the next year
  EXPECT_EQ(second.run_seed, 77u);
}

TEST(SceneRuns, ARunBeforeThePreviousEndedIsAnErrorAtItsTime) {
  json doc = TwoRuns();
  doc["frames"] = 25 * 3600;  // the first run lasts an hour: 09:00 to 10:00
  doc["runs"][1]["time_of_day_h"] = 9.5;
  const std::string text = ErrorOf(doc);
  EXPECT_NE(
      text.find("test.json: /runs/1/time_of_day_h: run 1 starts at day 0 09:30, before run 0 ends at day 0 10:00; "
                "expected a later time or day (/runs/1/day)"),
      std::string::npos)
      << text;
  doc["runs"][0]["day"] = 1;
  EXPECT_NE(ErrorOf(doc).find("test.json: /runs/0/day: the first run's day is day 0"), std::string::npos);
}

TEST(SceneRuns, OverridesOfWhatAllRunsShareAreRefusedAndABadOneIsReportedUnderItsRun) {
  json doc = TwoRuns();
  doc["runs"][1]["set"] = {
      {"camera.width_px", 320}, {"/room/size_m", {8, 3, 2.6}}, {"room", json::object()}, {"room.sun.time_of_day_h", 3}};
  std::string text = ErrorOf(doc);
  for (const char* expected :
       {"test.json: /runs/1/set/camera.width_px: sets /camera, which is one for all runs",
        "test.json: /runs/1/set//room/size_m: sets /room/size_m, which is one for all runs",
        "test.json: /runs/1/set/room: sets /room/sun/time_of_day_h, which is one for all runs",
        "test.json: /runs/1/set/room.sun.time_of_day_h: sets /room/sun/time_of_day_h, which is one for all runs (use "
        "/runs/N/time_of_day_h)"}) {
    EXPECT_NE(text.find(expected), std::string::npos) << expected << "\n" << text;
  }
  doc["runs"][1]["set"] = {{"crowd.people_per_table", 99}};
  text = ErrorOf(doc);
  EXPECT_NE(
      text.find(
          "test.json: /runs/1: its scene (the scene with /runs/1/set applied): test.json: /crowd/people_per_table"),
      std::string::npos)
      << text;
}

TEST(SceneRuns, TheSunsTimeIsTheFirstRunsAndAnotherIsRefused) {
  const Scene scene = SceneFromJson(TwoRuns(), "test.json");
  EXPECT_EQ(scene.room.sun.time_of_day_h, 9.0);
  EXPECT_EQ(scene.resolved["room"]["sun"]["time_of_day_h"], 9.0);
  // The resolved scene (a dataset's scene.json) reads back as the same scene.
  EXPECT_EQ(SceneFromJson(scene.resolved, "scene.json").resolved, scene.resolved);

  json doc = TwoRuns();
  doc["room"]["sun"]["time_of_day_h"] = 12;
  const std::string where =
      "test.json: /room/sun/time_of_day_h: is 12.00, but a scene with runs takes each run's time "
      "of day from /runs/N/time_of_day_h (the first run's is 9.00); remove it";
  EXPECT_NE(ErrorOf(doc).find(where), std::string::npos) << ErrorOf(doc);
  EXPECT_NE(ErrorOf(TwoRuns(), {"room.sun.time_of_day_h=12"}).find(where), std::string::npos);
  EXPECT_TRUE(ErrorOf(TwoRuns(), {"runs.1.time_of_day_h=20"}).empty());
  EXPECT_TRUE(ErrorOf(TwoRuns(), {"room.sun.time_of_day_h=9"}).empty());
}

TEST(SceneRuns, MoreThanAMillionFramesInAllIsAnError) {
  json doc = TwoRuns();
  doc["frames"] = 600000;
  doc["runs"][1]["frames"] = 600000;
  doc["runs"][1]["day"] = 1;
  EXPECT_NE(ErrorOf(doc).find("test.json: /runs: the runs hold 1200000 frames in all; expected at most 1000000"),
            std::string::npos);
}

}  // namespace
}  // namespace hoilcd
