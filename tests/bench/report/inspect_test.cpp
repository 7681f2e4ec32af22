#include "hoilcd/bench/report/inspect.h"

#include <cmath>

#include <gtest/gtest.h>

#include "hoilcd/bench/evaluation/query_conditions.h"
#include "hoilcd/sim/robot/robot.h"
#include "hoilcd/sim/scene/scene_options.h"
#include "hoilcd/sim/sensor/radiometry.h"
#include "hoilcd/sim/world/world.h"
#include "test_dir.h"
#include "tiny_room.h"

namespace hoilcd {
namespace {

constexpr int kFramesPerLap = 200;

// Two clockwise laps of a 1 m circle; the second lap's true path is `lap_offset_m` further out
// and the odometry drifts linearly along +x to `end_drift_m`; the camera rolls +-roll_rad.
std::vector<PoseRecord> TwoLaps(double lap_offset_m, double end_drift_m, double roll_rad) {
  std::vector<PoseRecord> poses;
  const int n = 2 * kFramesPerLap;
  for (int i = 0; i < n; ++i) {
    const double angle = -2.0 * M_PI * i / kFramesPerLap;
    const double radius = i < kFramesPerLap ? 1.0 : 1.0 + lap_offset_m;
    PoseRecord p;
    p.frame = i;
    p.time_s = i;
    p.x_m = 3.0 + radius * std::cos(angle);
    p.y_m = 1.5 + radius * std::sin(angle);
    p.theta_rad = std::remainder(angle - M_PI / 2, 2 * M_PI);
    p.odo_x_m = p.x_m + end_drift_m * i / (n - 1);
    p.odo_y_m = p.y_m;
    p.odo_theta_rad = p.theta_rad;
    p.cam_roll_rad = (i % 2 ? 1 : -1) * roll_rad;
    p.cam_z_m = 0.95;
    poses.push_back(p);
  }
  return poses;
}

double Figure(const InspectSection& s, const std::string& key) {
  const InspectFigure* f = s.Find(key);
  EXPECT_NE(f, nullptr) << key;
  return f ? f->value : NAN;
}

TEST(Inspect, TrajectoryMeasuresLapDifferenceAndDrift) {
  const InspectSection s = TrajectorySection(TwoLaps(0.05, 0.3, 0));
  EXPECT_EQ(Figure(s, "frames"), 400);
  EXPECT_EQ(Figure(s, "laps"), 2);
  // Lap 2 is a concentric circle 5 cm out; the first lap's polyline (chords) is slightly inside.
  EXPECT_NEAR(Figure(s, "lap_difference_median_m"), 0.05, 0.001);
  EXPECT_NEAR(Figure(s, "lap_difference_p90_m"), 0.05, 0.001);
  EXPECT_NEAR(Figure(s, "odometry_drift_end_m"), 0.3, 1e-12);
  EXPECT_NEAR(Figure(s, "odometry_drift_max_m"), 0.3, 1e-12);
  EXPECT_NEAR(Figure(s, "path_length_m"), 2 * M_PI * 2.05, 0.05);
  EXPECT_NEAR(Figure(s, "odometry_drift_end_pct"), 100 * 0.3 / Figure(s, "path_length_m"), 1e-9);
}

TEST(Inspect, CameraJitterIsTheStdAndFrameToFrameChangeOfRoll) {
  const InspectSection s = CameraSection(TwoLaps(0, 0, 0.01));
  EXPECT_NEAR(Figure(s, "roll_std_deg"), 0.01 * 180 / M_PI, 1e-3);
  EXPECT_NEAR(Figure(s, "roll_frame_to_frame_rms_deg"), 0.02 * 180 / M_PI, 1e-9);
  EXPECT_NEAR(Figure(s, "pitch_std_deg"), 0, 1e-12);
  EXPECT_NEAR(Figure(s, "height_std_m"), 0, 1e-12);
}

TEST(Inspect, PeopleCountsPerFrameAndOcclusionHistogram) {
  std::vector<FramePersons> persons(3);
  for (int f = 0; f < 3; ++f) persons[f].frame = f;
  persons[0].persons.resize(2);
  persons[0].persons[0].occlusion_fraction = 0.1;
  persons[0].persons[1].occlusion_fraction = 1.0;
  persons[2].persons.resize(1);
  persons[2].persons[0].occlusion_fraction = 0.5;
  const InspectSection s = PeopleSection(persons, 3);
  EXPECT_EQ(Figure(s, "per_frame_mean"), 1.0);
  EXPECT_EQ(Figure(s, "per_frame_min"), 0);
  EXPECT_EQ(Figure(s, "per_frame_max"), 2);
  const InspectFigure* h = s.Find("occlusion_histogram");
  ASSERT_NE(h, nullptr);
  EXPECT_EQ(h->counts, (std::vector<int64_t>{1, 0, 1, 0, 1}));
}

TEST(Inspect, LabelsDisagreeOnlyWhenOdometryDrifts) {
  EXPECT_EQ(Figure(LabelSection(TwoLaps(0, 0, 0), ProtocolOptions()), "queries_differing"), 0);
  const InspectSection drifting = LabelSection(TwoLaps(0, 0.3, 0), ProtocolOptions());
  EXPECT_GT(Figure(drifting, "queries_differing"), 100);
  EXPECT_EQ(Figure(drifting, "queries"), kFramesPerLap);
}

TEST(Inspect, JsonHasOneObjectPerSectionAndHistogramsWithEdges) {
  InspectReport r;
  r.sections.push_back(TrajectorySection(TwoLaps(0.05, 0.3, 0)));
  r.sections.push_back(PeopleSection({}, 2));
  const nlohmann::json j = r.ToJson();
  EXPECT_NEAR(j["trajectory"]["lap_difference_median_m"].get<double>(), 0.05, 0.001);
  EXPECT_EQ(j["people"]["occlusion_histogram"]["counts"].size(), 5u);
  EXPECT_EQ(j["people"]["occlusion_histogram"]["bin_edges"].size(), 6u);
  EXPECT_NE(r.ToText().find("lap-to-lap true path difference, median"), std::string::npos);
  EXPECT_NE(r.ToMarkdown().find("| odometry drift at the end |"), std::string::npos);
}

// Two recording runs: run 0 drives 1.25 laps of TwoLaps (its odometry drifting to 0.2 m over 400
// frames) with one person in view, run 1 starts at the dock again two hours later, its odometry
// restarting, and drives 1.5 laps (drift to 0.1 m over 400 frames) with three people in view.
struct TwoRuns {
  std::vector<RunRecord> runs = {{0, 250, 9.0, 0, 0, 1}, {250, 300, 15.5, 0, 7200, 2}};
  std::vector<PoseRecord> poses;
  std::vector<FramePersons> persons;
  TwoRuns() {
    const std::vector<PoseRecord> first = TwoLaps(0, 0.2, 0), second = TwoLaps(0, 0.1, 0);
    poses.assign(first.begin(), first.begin() + 250);
    for (int i = 0; i < 300; ++i) {
      PoseRecord p = second[i];
      p.frame += 250;
      p.time_s += 7200;
      p.run = 1;
      poses.push_back(p);
    }
    for (const PoseRecord& p : poses) persons.push_back({p.frame, std::vector<PersonRecord>(p.run == 0 ? 1 : 3)});
  }
};

TEST(Inspect, EachRecordingRunGetsItsLapsPathPeopleAndDriftAtItsEnd) {
  const TwoRuns two;
  const std::vector<InspectRun> runs = InspectRuns(two.runs, two.poses, &two.persons);
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0].laps, 2);                                // a lap and a quarter
  EXPECT_EQ(runs[1].laps, 2);                                // a lap and a half, counted from the dock again
  const double step_m = 2 * std::sin(M_PI / kFramesPerLap);  // a chord of the circle
  EXPECT_NEAR(runs[0].path_length_m, 249 * step_m, 1e-9);
  EXPECT_NEAR(runs[1].path_length_m, 299 * step_m, 1e-9);
  EXPECT_NEAR(runs[0].odometry_drift_end_m, 0.2 * 249 / 399, 1e-12);
  EXPECT_NEAR(runs[1].odometry_drift_end_m, 0.1 * 299 / 399, 1e-12);
  EXPECT_NEAR(runs[1].odometry_drift_end_pct, 100 * runs[1].odometry_drift_end_m / runs[1].path_length_m, 1e-12);
  EXPECT_EQ(runs[0].people_per_frame_mean, 1);
  EXPECT_EQ(runs[1].people_per_frame_mean, 3);
  EXPECT_TRUE(std::isnan(InspectRuns(two.runs, two.poses, nullptr)[1].people_per_frame_mean));
  // The whole sequence: the carrying back to the dock (1.4 m) is not driven, and the drift at the
  // end is over the last run's path, since its odometry restarted at the dock.
  const InspectSection t = TrajectorySection(two.poses);
  EXPECT_EQ(Figure(t, "laps"), 4);
  EXPECT_NEAR(Figure(t, "path_length_m"), runs[0].path_length_m + runs[1].path_length_m, 1e-9);
  EXPECT_NEAR(Figure(t, "odometry_drift_end_pct"), runs[1].odometry_drift_end_pct, 1e-9);

  InspectReport r;
  r.sections.push_back(t);
  r.runs = runs;
  const nlohmann::json j = r.ToJson();
  ASSERT_EQ(j["runs"].size(), 2u);
  EXPECT_EQ(j["runs"][1]["first_frame"], 250);
  EXPECT_EQ(j["runs"][1]["time_of_day_h"], 15.5);
  EXPECT_EQ(j["runs"][1]["start_time_s"], 7200);
  EXPECT_EQ(j["runs"][1]["laps"], 2);
  EXPECT_EQ(j["runs"][1]["people_per_frame_mean"], 3);
  EXPECT_NE(
      r.ToText().find("Recording runs\n  run 0: recorded day 0, 09:00, frames 0-249, starts after 0.00 h, laps 2"),
      std::string::npos)
      << r.ToText();
  EXPECT_NE(r.ToMarkdown().find("### Recording runs"), std::string::npos);
  EXPECT_NE(r.ToMarkdown().find("| 1 | day 0, 15:30 | 250-549 | 2.00 h | 2 | 9.4 m | 3.00 | 0.075 m (0.80 %) |"),
            std::string::npos)
      << r.ToMarkdown();
}

TEST(Inspect, OneRecordingRunAddsNothing) {
  const std::vector<PoseRecord> poses = TwoLaps(0, 0.2, 0);
  EXPECT_TRUE(InspectRuns(SingleRun(400), poses, nullptr).empty());
  InspectReport r;
  r.sections.push_back(TrajectorySection(poses));
  EXPECT_FALSE(r.ToJson().contains("runs"));
  EXPECT_EQ(r.ToText().find("Recording runs"), std::string::npos);
  EXPECT_EQ(r.ToMarkdown().find("Recording runs"), std::string::npos);
}

// The paper room's robot as rendered (scene defaults, furniture as obstacles).
std::vector<PoseRecord> ScenePoses(const std::string& scene_name, const std::vector<std::string>& overrides = {}) {
  const Scene scene = LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/" + scene_name, overrides);
  const BandRadianceTable table;
  const World world(scene, table);
  return PoseRecordsOf(SimulateSceneRobot(scene, world.obstacles()));
}

// The documented bands (docs/models/robot.md) of the paper room's defaults, for the seeds the docs use.
TEST(PaperRoomDefaults, LapDifferenceDriftAndJitterLieInTheDocumentedBands) {
  for (const char* seed : {"seed=1", "seed=2"}) {
    const std::vector<PoseRecord> poses = ScenePoses("paper_room.json", {seed});
    const InspectSection t = TrajectorySection(poses);
    EXPECT_GE(Figure(t, "lap_difference_median_m"), 0.03) << seed;
    EXPECT_LE(Figure(t, "lap_difference_median_m"), 0.30) << seed;
    EXPECT_GE(Figure(t, "odometry_drift_max_m"), 0.10) << seed;
    EXPECT_LE(Figure(t, "odometry_drift_max_m"), 2.00) << seed;
    const InspectSection c = CameraSection(poses);
    EXPECT_GT(Figure(c, "roll_frame_to_frame_rms_deg"), 0.05) << seed;
    EXPECT_GT(Figure(c, "pitch_frame_to_frame_rms_deg"), 0.05) << seed;
    EXPECT_GT(Figure(LabelSection(poses, ProtocolOptions()), "queries_differing"), 0) << seed;
  }
}

TEST(IdealRoom, LapsRepeatOdometryIsExactCameraIsRigidAndLabelsAgree) {
  const std::vector<PoseRecord> poses = ScenePoses("ideal_room.json");
  const InspectSection t = TrajectorySection(poses);
  EXPECT_LT(Figure(t, "lap_difference_median_m"), 0.005);
  EXPECT_EQ(Figure(t, "odometry_drift_max_m"), 0);
  EXPECT_EQ(Figure(CameraSection(poses), "roll_std_deg"), 0);
  EXPECT_EQ(Figure(LabelSection(poses, ProtocolOptions()), "queries_differing"), 0);
}

TEST(Inspect, ViewsCountTheBlankFramesOfTheEvenlySampledExrs) {
  const test::TestDir temp;
  const Dataset dataset = test::TinyRoomDataset(temp / "dataset");
  const InspectSection views = ViewSection(dataset, 2);
  const int frames = dataset.num_frames();  // 440: every frame is sampled (at most 400 a step of 2)
  const int step = (frames + kViewFramesSampled - 1) / kViewFramesSampled;
  int sampled = 0, blank = 0, bare = 0;
  for (int f = 0; f < frames; f += step, ++sampled) {
    const QueryConditions c = ImageConditionsOf(dataset, f);
    blank += c.blank;
    bare += c.structure_only_classes;
  }
  EXPECT_EQ(views.Find("frames_sampled")->value, sampled);
  EXPECT_DOUBLE_EQ(views.Find("blank_percent")->value, 100.0 * blank / sampled);
  EXPECT_DOUBLE_EQ(views.Find("bare_percent")->value, 100.0 * bare / sampled);
  EXPECT_GE(bare, blank);                                  // a blank view is a bare one with little spread
  EXPECT_GT(views.Find("with_people_percent")->value, 0);  // the tiny room's camera faces its table
  EXPECT_GT(views.Find("spread_median_k")->value, kBlankSpreadK);
  // The same at one thread, and in the dataset's inspect report.
  EXPECT_EQ(ViewSection(dataset, 1).Find("blank_percent")->value, views.Find("blank_percent")->value);
  ASSERT_NE(InspectDataset(dataset).Find("views"), nullptr);
}

// Whiteboards on the four walls of the tiny room: with people at the table the boards behind them
// mirror them, so their true temperature spreads; with nobody there a board is nearly uniform.
TEST(Inspect, ReflectionSectionSeesPeopleMirroredInWhiteboards) {
  const std::string boards =
      "objects=[{\"asset\": \"whiteboard\", \"position_m\": [0.0, 1.8, 0.9], \"yaw_deg\": 0},"
      "{\"asset\": \"whiteboard\", \"position_m\": [4.4, 1.8, 0.9], \"yaw_deg\": 180},"
      "{\"asset\": \"whiteboard\", \"position_m\": [2.2, 0.0, 0.9], \"yaw_deg\": 90},"
      "{\"asset\": \"whiteboard\", \"position_m\": [2.2, 3.6, 0.9], \"yaw_deg\": -90}]";
  const test::TestDir temp;
  double spread_max[2];
  for (int people = 0; people < 2; ++people) {
    const Dataset dataset =
        test::TinyRoomDataset(temp / ("dataset" + std::to_string(people)),
                              {boards, "frames=220", people ? "crowd.people_per_table=4" : "crowd.people_per_table=0"});
    const InspectSection thermal = ReflectionSection(dataset, 2);
    ASSERT_NE(thermal.Find("whiteboard_views"), nullptr);
    EXPECT_GT(thermal.Find("whiteboard_views")->value, 20);
    EXPECT_EQ(thermal.Find("window_views")->value, 0);  // the tiny room has no window
    ASSERT_NE(thermal.Find("whiteboard_spread_max_k"), nullptr);
    spread_max[people] = thermal.Find("whiteboard_spread_max_k")->value;
    EXPECT_LE(thermal.Find("whiteboard_spread_median_k")->value, spread_max[people]);
    EXPECT_EQ(ReflectionSection(dataset, 1).Find("whiteboard_spread_max_k")->value, spread_max[people]);
  }
  // A board mirroring only the room spreads by 12 % of the walls' 2.5 K stratification and the table.
  EXPECT_LT(spread_max[0], 0.5) << "a board mirroring only the room is nearly uniform";
  EXPECT_GT(spread_max[1], spread_max[0] + 0.5)
      << "a board behind seated people mirrors them: " << spread_max[1] << " K";
}

// The tiny room's people wear garments (scene defaults): their clothing varies within itself.
TEST(Inspect, ClothingSectionMeasuresTheSpreadWithinAPersonsClothing) {
  const test::TestDir temp;
  const Dataset dataset = test::TinyRoomDataset(temp / "dataset");
  const InspectSection clothing = ClothingSection(dataset, 2);
  EXPECT_GT(clothing.Find("neighbour_pairs")->value, 100);
  EXPECT_LT(clothing.Find("equal_neighbours_percent")->value, 50);
  EXPECT_GT(clothing.Find("spread_median_k")->value, 1.0);
  EXPECT_EQ(ClothingSection(dataset, 1).Find("equal_neighbours_percent")->value,
            clothing.Find("equal_neighbours_percent")->value);
  ASSERT_NE(InspectDataset(dataset).Find("clothing"), nullptr);
}

}  // namespace
}  // namespace hoilcd
