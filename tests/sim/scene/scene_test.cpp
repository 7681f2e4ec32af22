#include "hoilcd/sim/scene/scene.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "hoilcd/sim/scene/scene_options.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

using nlohmann::json;

std::string ScenePath(const std::string& name) { return std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/" + name; }

std::vector<Problem> ProblemsOf(const json& doc, const std::vector<std::string>& overrides = {}) {
  try {
    SceneFromJson(doc, "test.json", overrides);
  } catch (const InputError& e) {
    return e.problems();
  }
  return {};
}

bool HasProblem(const std::vector<Problem>& problems, const std::string& where, const std::string& fragment) {
  for (const Problem& p : problems) {
    if (p.where == where && p.message.find(fragment) != std::string::npos) return true;
  }
  return false;
}

TEST(Scene, EveryShippedSceneIsValid) {
  for (const auto& entry : std::filesystem::directory_iterator(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes")) {
    if (entry.path().extension() != ".json" || entry.path().filename() == "scene.schema.json") continue;
    EXPECT_NO_THROW(LoadScene(entry.path().string())) << entry.path();
  }
}

TEST(Scene, EmptyDocumentIsThePaperRoomByDefaults) {
  const Scene s = SceneFromJson(json::object(), "empty.json");
  EXPECT_EQ(s.frames, 1996);
  EXPECT_DOUBLE_EQ(s.frame_rate_hz, 25.0);
  EXPECT_EQ(s.tables.size(), 6u);
  EXPECT_EQ(s.crowd.people_per_table, 4);
  EXPECT_DOUBLE_EQ(s.room.size_m.x(), 7.0);
  EXPECT_DOUBLE_EQ(s.room.size_m.y(), 3.0);
  EXPECT_EQ(s.camera.width_px, 256);
  EXPECT_EQ(s.camera.height_px, 192);
  // The resolved document has every default filled in.
  EXPECT_TRUE(s.resolved["camera"].contains("netd_k"));
  EXPECT_TRUE(s.resolved["robot"].contains("wheelbase_m"));
}

// paper_room is the schema's defaults but for its objects: what such a meeting room holds.
TEST(Scene, PaperRoomFileEqualsTheDefaultsItDocumentsButForItsObjects) {
  const Scene file = LoadScene(ScenePath("paper_room.json"));
  json doc = json::object();
  doc["name"] = file.name;
  doc["description"] = file.resolved["description"];
  doc["objects"] = file.resolved["objects"];
  EXPECT_EQ(file.hash, SceneFromJson(doc, "x.json").hash);
}

TEST(Scene, UnknownKeyIsAnErrorNamingTheKeyAndItsPath) {
  const auto problems = ProblemsOf(json{{"crowd", {{"people_per_tabel", 3}}}});
  ASSERT_FALSE(problems.empty());
  EXPECT_TRUE(HasProblem(problems, "test.json: /crowd", "unknown key 'people_per_tabel'"))
      << problems.front().ToString();
  EXPECT_TRUE(HasProblem(problems, "test.json: /crowd", "people_per_table"));
}

TEST(Scene, WrongTypeAndOutOfRangeValuesAreReportedTogether) {
  const auto problems =
      ProblemsOf(json{{"frames", "many"}, {"crowd", {{"people_per_table", 9}}}, {"camera", {{"netd_k", -1}}}});
  EXPECT_TRUE(HasProblem(problems, "test.json: /frames", ""));
  EXPECT_TRUE(HasProblem(problems, "test.json: /crowd/people_per_table", ""));
  EXPECT_TRUE(HasProblem(problems, "test.json: /camera/netd_k", ""));
  EXPECT_EQ(problems.size(), 3u);
}

TEST(Scene, CrossFieldProblemsNameTheirPaths) {
  EXPECT_TRUE(HasProblem(ProblemsOf(json{{"camera", {{"display_min_c", 30}, {"display_max_c", 20}}}}),
                         "test.json: /camera/display_max_c", "greater"));
  EXPECT_TRUE(HasProblem(ProblemsOf(json{{"tables", {{{"center_m", {9.0, 1.0}}}}}}), "test.json: /tables/0/center_m",
                         "inside the room"));
  EXPECT_TRUE(HasProblem(ProblemsOf(json{{"crowd", {{"seating", {{{"table", 7}, {"seat", 0}}}}}}}),
                         "test.json: /crowd/seating/0/table", "below 6"));
  EXPECT_TRUE(HasProblem(ProblemsOf(json{{"route", {{"waypoints_m", {{0.5, 0.5}, {8.0, 0.5}}}}}}),
                         "test.json: /route/waypoints_m/1", "inside the room"));
}

TEST(Scene, RobotErrorModelAndVibrationProblemsNameTheirPaths) {
  EXPECT_TRUE(HasProblem(ProblemsOf(json{{"odometry", {{"slip_noise_frac", -1}}}}),
                         "test.json: /odometry/slip_noise_frac", ""));
  EXPECT_TRUE(HasProblem(ProblemsOf(json{{"odometry", {{"heading_noise_deg_sqrt_m", -0.1}}}}),
                         "test.json: /odometry/heading_noise_deg_sqrt_m", ""));
  EXPECT_TRUE(HasProblem(ProblemsOf(json{{"robot", {{"navigation", "gps"}}}}), "test.json: /robot/navigation", ""));
  EXPECT_TRUE(HasProblem(ProblemsOf(json{{"robot", {{"vibration", {{"damping_ratio", 0}}}}}}),
                         "test.json: /robot/vibration/damping_ratio", ""));
  EXPECT_TRUE(HasProblem(ProblemsOf(json{{"robot", {{"vibration", {{"shake", 1}}}}}}), "test.json: /robot/vibration",
                         "unknown key 'shake'"));
  EXPECT_TRUE(HasProblem(ProblemsOf(json{{"robot", {{"localization", {{"interval_s", 0}}}}}}),
                         "test.json: /robot/localization/interval_s", ""));
  EXPECT_TRUE(HasProblem(ProblemsOf(json{{"robot", {{"localization", {{"position_sd_m", -0.01}}}}}}),
                         "test.json: /robot/localization/position_sd_m", ""));
  EXPECT_TRUE(HasProblem(ProblemsOf(json{{"robot", {{"localization", {{"heading_sd_deg", 31}}}}}}),
                         "test.json: /robot/localization/heading_sd_deg", ""));
  EXPECT_TRUE(HasProblem(ProblemsOf(json{{"robot", {{"localization", {{"correlation_s", -1}}}}}}),
                         "test.json: /robot/localization/correlation_s", ""));
  EXPECT_TRUE(HasProblem(ProblemsOf(json{{"robot", {{"localization", {{"gps", 1}}}}}}),
                         "test.json: /robot/localization", "unknown key 'gps'"));
}

// Every navigation name reaches the options; the shipped default is localised.
TEST(SceneOptions, NavigationNamesMapToTheirModesAndLocalizedIsTheDefault) {
  EXPECT_EQ(TricycleOptionsFromScene(SceneFromJson(json::object(), "test.json")).navigation,
            TricycleOptions::Navigation::kLocalized);
  EXPECT_EQ(
      TricycleOptionsFromScene(SceneFromJson(json{{"robot", {{"navigation", "odometry"}}}}, "test.json")).navigation,
      TricycleOptions::Navigation::kOdometry);
  EXPECT_EQ(TricycleOptionsFromScene(SceneFromJson(json{{"robot", {{"navigation", "ground_truth"}}}}, "test.json"))
                .navigation,
            TricycleOptions::Navigation::kGroundTruth);
  const TricycleOptions robot = TricycleOptionsFromScene(
      SceneFromJson(json{{"robot", {{"localization", {{"interval_s", 2}, {"heading_sd_deg", 0.5}}}}}}, "test.json"));
  EXPECT_EQ(robot.localization.interval_s, 2);
  EXPECT_EQ(robot.localization.heading_sd_deg, 0.5);
  EXPECT_EQ(robot.localization.position_sd_m, LocalizationOptions().position_sd_m);  // schema default = struct default
  EXPECT_EQ(robot.localization.correlation_s, LocalizationOptions().correlation_s);
}

// A steering offset beyond the steering limit passes the schema's own ranges but not the robot.
TEST(SceneOptions, SteeringOffsetBeyondTheSteeringLimitNamesItsPointer) {
  const Scene scene = SceneFromJson(
      json{{"robot", {{"max_steer_deg", 8}}}, {"odometry", {{"steer_offset_deg", 5}, {"error_scale", 2}}}},
      "test.json");
  try {
    OdometryOptionsFromScene(scene);
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    ASSERT_EQ(e.problems().size(), 1u);
    EXPECT_EQ(e.problems()[0].where, "test.json: /odometry/steer_offset_deg");
    EXPECT_NE(e.problems()[0].message.find("must stay below /robot/max_steer_deg"), std::string::npos);
  }
}

TEST(SceneOptions, AnOptionsCheckNamesTheFieldsPointer) {
  const Scene scene = SceneFromJson(json{{"robot", {{"vibration", {{"reference_speed_m_s", 1e-300}}}}}}, "test.json");
  TricycleOptions robot = TricycleOptionsFromScene(scene);  // valid: tiny but positive
  EXPECT_GT(robot.vibration.reference_speed_m_s, 0);
  // The robot table checks while the scene is typed, every problem at its pointer.
  try {
    SceneFromJson(json{{"robot", {{"base_to_rear_m", 0.5}}}}, "test.json");
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    ASSERT_EQ(e.problems().size(), 1u);
    EXPECT_EQ(e.problems()[0].ToString(), "test.json: /robot/base_to_rear_m: must be below length_m");
  }
}

TEST(Scene, OverridesSetValuesByDottedPathOrPointer) {
  const Scene a = SceneFromJson(json::object(), "x.json", {"crowd.people_per_table=2"});
  EXPECT_EQ(a.crowd.people_per_table, 2);
  const Scene b = SceneFromJson(json::object(), "x.json", {"/camera/netd_k=0.05", "name=other"});
  EXPECT_DOUBLE_EQ(b.camera.sensor.netd_k, 0.05);
  EXPECT_EQ(b.name, "other");
  const Scene c =
      SceneFromJson(LoadScene(ScenePath("paper_room.json")).resolved, "x.json", {"tables.0.center_m=[1.5, 1.4]"});
  EXPECT_DOUBLE_EQ(c.tables[0].center_m.x(), 1.5);
  EXPECT_NE(a.hash, b.hash);
}

TEST(Scene, BadOverridesAreErrorsNamingTheOverride) {
  try {
    SceneFromJson(json::object(), "x.json", {"crowd.people_per_table"});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.problems().at(0).where, "--set crowd.people_per_table");
    EXPECT_NE(e.problems().at(0).message.find("KEY=VALUE"), std::string::npos);
  }
  // A value of the wrong type is caught by validation at the overridden path.
  EXPECT_TRUE(
      HasProblem(ProblemsOf(json::object(), {"crowd.people_per_table=lots"}), "x.json: /crowd/people_per_table", "") ||
      !ProblemsOf(json::object(), {"crowd.people_per_table=lots"}).empty());
  try {
    SceneFromJson(LoadScene(ScenePath("paper_room.json")).resolved, "x.json", {"tables.9.yaw_deg=1"});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("index below 6"), std::string::npos) << e.what();
  }
}

TEST(Scene, MissingAndMalformedFilesAreErrorsNamingTheFile) {
  try {
    LoadScene("/nonexistent/scene.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.problems().at(0).where, "/nonexistent/scene.json");
  }
  const test::TestDir temp;
  const std::string path = temp / "bad_scene.json";
  std::ofstream(path) << "{ \"frames\": 10, ";
  try {
    LoadScene(path);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.problems().at(0).where, path);
    EXPECT_NE(e.problems().at(0).message.find("valid JSON"), std::string::npos);
  }
  std::ofstream(path) << "[1, 2]";
  EXPECT_THROW(LoadScene(path), InputError);
}

TEST(Scene, HashDependsOnResolvedContentOnly) {
  const Scene a = SceneFromJson(json{{"seed", 1}}, "a.json");
  const Scene b = SceneFromJson(json::object(), "b.json");  // seed 1 by default
  EXPECT_EQ(a.hash, b.hash);
  EXPECT_NE(a.hash, SceneFromJson(json{{"seed", 2}}, "a.json").hash);
}

TEST(Scene, DistractorSwitchesRemoveTheirObjects) {
  const Scene all = SceneFromJson(json::object(), "x.json");
  const Scene no_cups = SceneFromJson(json{{"distractors", {{"cups", false}}}}, "x.json");
  int cups = 0;
  for (const ObjectSpec& o : all.objects) cups += o.asset == "cup";
  EXPECT_GT(cups, 0);
  EXPECT_EQ(no_cups.objects.size(), all.objects.size() - cups);
}

TEST(Scene, OverridingOneElementOfADefaultArrayKeepsTheOthers) {
  const Scene all = SceneFromJson(json::object(), "x.json");
  const Scene one_off = SceneFromJson(json::object(), "x.json", {"objects.0.enabled=false"});
  EXPECT_EQ(one_off.objects.size(), all.objects.size() - 1);
}

TEST(Scene, AnAbsurdArrayIndexInAnOverrideIsAnInputError) {
  EXPECT_THROW(SceneFromJson(json::object(), "x.json", {"route.waypoints_m.99999999999999999999=1"}), InputError);
}

TEST(Scene, RequiredPropertiesAreEnforcedBeforeDefaultsFillThemIn) {
  const auto problems = ProblemsOf(json{{"tables", {{{"yaw_deg", 0}}}},
                                        {"objects", {{{"asset", "cup"}}}},
                                        {"room", {{"windows", {{{"wall", "north"}}}}}},
                                        {"crowd", {{"seating", {{{"table", 0}}}}, {"standing", {json::object()}}}}});
  EXPECT_TRUE(HasProblem(problems, "test.json: /tables/0", "missing required property 'center_m'"));
  EXPECT_TRUE(HasProblem(problems, "test.json: /objects/0", "missing required property 'position_m'"));
  EXPECT_TRUE(HasProblem(problems, "test.json: /room/windows/0", "missing required property 'center_m'"));
  EXPECT_TRUE(HasProblem(problems, "test.json: /crowd/seating/0", "missing required property 'seat'"));
  EXPECT_TRUE(HasProblem(problems, "test.json: /crowd/standing/0", "missing required property 'position_m'"));
}

TEST(Scene, ValuesThatWouldHangTheSimulatorAreRejected) {
  EXPECT_TRUE(
      HasProblem(ProblemsOf(json::object(), {"camera.ffc_interval_s=1e308"}), "test.json: /camera/ffc_interval_s", ""));
  EXPECT_TRUE(HasProblem(ProblemsOf(json::object(), {"crowd.posture_change_interval_s=1e-9"}),
                         "test.json: /crowd/posture_change_interval_s", "at least 1 s"));
  EXPECT_TRUE(HasProblem(ProblemsOf(json{{"objects", {{{"asset", "cup"}, {"position_m", {1e308, 1, 0.7}}}}}}),
                         "test.json: /objects/0/position_m", "inside the room"));
  EXPECT_TRUE(HasProblem(ProblemsOf(json{{"crowd", {{"standing", {{{"position_m", {1, -1e308}}}}}}}}),
                         "test.json: /crowd/standing/0/position_m", "inside the room"));
}

TEST(Scene, MissingAssetIsNamedAtItsJsonPath) {
  const auto problems = ProblemsOf(json{{"objects", {{{"asset", "no_such_thing"}, {"position_m", {1, 1, 0.7}}}}},
                                        {"furniture", {{"chair_asset", "missing_chair.gltf"}}}});
  EXPECT_TRUE(HasProblem(problems, "test.json: /objects/0/asset", "no_such_thing.gltf does not exist"));
  EXPECT_TRUE(HasProblem(problems, "test.json: /furniture/chair_asset", "missing_chair.gltf does not exist"));
}

TEST(Scene, TypeErrorsNameTheExpectedType) {
  const auto problems = ProblemsOf(json{{"frames", "many"}, {"camera", {{"netd_k", "low"}}}, {"name", 3}});
  EXPECT_TRUE(HasProblem(problems, "test.json: /frames", "expected a whole number"));
  EXPECT_TRUE(HasProblem(problems, "test.json: /camera/netd_k", "expected a number"));
  EXPECT_TRUE(HasProblem(problems, "test.json: /name", "expected a string"));
}

TEST(Scene, NumberTooLargeForADoubleIsAnInputErrorNamingTheFile) {
  const test::TestDir temp;
  const std::string path = temp / "overflow.json";
  std::ofstream(path) << "{ \"frame_rate_hz\": 1e400 }";
  try {
    LoadScene(path);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.problems().at(0).where, path);
    EXPECT_NE(e.problems().at(0).message.find("valid JSON"), std::string::npos);
  }
}

TEST(Scene, AnIndexPastTheEndOfTheDocumentIsAnInputErrorNotAHugeArray) {
  // Found by fuzz_scene: a numeric token under a missing key made nlohmann allocate an array
  // of that many elements.
  const auto problems = ProblemsOf(json::object(), {"nothing.111111111111111=1"});
  EXPECT_TRUE(HasProblem(problems, "--set nothing.111111111111111=1", "an existing array at /nothing"));
}

TEST(Scene, DoorsOffTheWallsOrTooWideOrNarrowAreErrorsNamingTheDoor) {
  auto doors = [](const json& list) { return ProblemsOf(json{{"room", {{"doors", list}}}}); };
  EXPECT_TRUE(HasProblem(doors({{{"position_m", {3.0, 1.5}}}}), "test.json: /room/doors/0/position_m",
                         "a point on one of the room's walls (x = 0 or 7, or y = 0 or 3"));
  EXPECT_TRUE(HasProblem(doors({{{"position_m", {7.0, 1.5}}}, {{"position_m", {7.5, 1.5}}}}),
                         "test.json: /room/doors/1/position_m", "a point on one of the room's walls"));
  EXPECT_TRUE(HasProblem(doors({{{"position_m", {7.0, 0.3}}, {"width_m", 0.9}}}), "test.json: /room/doors/0/width_m",
                         "to fit along its wall (length 3 m) without reaching a corner"));
  EXPECT_TRUE(
      HasProblem(doors({{{"position_m", {3.5, 0.0}}, {"width_m", 0.5}}}), "test.json: /room/doors/0/width_m", ""));
  EXPECT_TRUE(
      HasProblem(doors({{{"position_m", {3.5, 0.0}}, {"width_m", 3.5}}}), "test.json: /room/doors/0/width_m", ""));
  EXPECT_TRUE(
      HasProblem(doors({{{"width_m", 0.9}}}), "test.json: /room/doors/0", "missing required property 'position_m'"));
  EXPECT_TRUE(doors({{{"position_m", {0.0, 1.5}}}, {{"position_m", {3.5, 3.0}}, {"width_m", 1.6}}}).empty());
}

TEST(Scene, WithoutDoorsTheRoomHasOneInTheMiddleOfEachEndWallNamedInTheResolvedScene) {
  const Scene scene = SceneFromJson(json{{"room", {{"size_m", {8.0, 4.0, 2.6}}}}}, "test.json");
  ASSERT_EQ(scene.room.doors.size(), 2u);
  EXPECT_EQ(scene.room.doors[0].position_m, Eigen::Vector2d(0.0, 2.0));
  EXPECT_EQ(scene.room.doors[1].position_m, Eigen::Vector2d(8.0, 2.0));
  EXPECT_EQ(scene.room.doors[1].width_m, 0.9);
  EXPECT_EQ(scene.resolved["room"]["doors"],
            json::parse(R"([{"position_m": [0.0, 2.0], "width_m": 0.9}, {"position_m": [8.0, 2.0], "width_m": 0.9}])"));
}

}  // namespace
}  // namespace hoilcd
