#include "hoilcd/core/dataset/runs.h"

#include <gtest/gtest.h>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/util/error.h"
#include "input_error_of.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

using test::InputErrorOf;

std::vector<RunRecord> ThreeRuns() {
  return {
      {0, 4, 9.0, 0, 0.0, 1}, {4, 3, 13.5, 0, 16200.0, 9007199254740991ull}, {7, 2, 8.25, 1, 84600.0 + 1.0 / 3.0, 7}};
}

TEST(RunsJson, RoundTripKeepsEveryFieldExactly) {
  const std::string text = RunsToJson(ThreeRuns());
  const std::vector<RunRecord> back = RunsFromJson(text, "runs.json", 9);
  ASSERT_EQ(back.size(), 3u);
  EXPECT_EQ(back[2].start_time_s, 84600.0 + 1.0 / 3.0);
  EXPECT_EQ(back[1].seed, 9007199254740991ull);
  EXPECT_EQ(back[2].day, 1);
  EXPECT_EQ(RunsToJson(back), text);
}

TEST(RunsJson, RunsThatDoNotTileTheFramesInTimeOrderAreReportedAtTheirPointers) {
  std::vector<RunRecord> runs = ThreeRuns();
  runs[1].first_frame = 5;
  runs[2].start_time_s = 100;
  const std::string message = InputErrorOf([&] { RunsFromJson(RunsToJson(runs), "DIR/runs.json", 9); });
  EXPECT_NE(message.find("DIR/runs.json: /runs/1/first_frame: expected 4"), std::string::npos) << message;
  EXPECT_NE(message.find("DIR/runs.json: /runs/2/start_time_s: expected a start after the previous run's"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("DIR/runs.json: /runs/2/first_frame: expected 8"), std::string::npos) << message;

  const std::string short_runs = InputErrorOf([&] { RunsFromJson(RunsToJson(ThreeRuns()), "DIR/runs.json", 10); });
  EXPECT_NE(short_runs.find("DIR/runs.json: /runs: the runs end at frame 9, expected 10"), std::string::npos)
      << short_runs;
  const std::string bad = InputErrorOf([&] {
    RunsFromJson(
        R"({"runs":[{"first_frame":0,"frames":0,"time_of_day_h":24,"day":-1,"start_time_s":0,"seed":1,"x":1}]})",
        "DIR/runs.json", 0);
  });
  for (const char* expected :
       {"/runs/0/x: unknown key", "/runs/0/frames: expected at least 1 frame",
        "/runs/0/time_of_day_h: expected an hour in [0, 24)", "/runs/0/day: expected a day >= 0"}) {
    EXPECT_NE(bad.find(expected), std::string::npos) << bad;
  }
  EXPECT_NE(InputErrorOf([&] { RunsFromJson(R"({"runs":[]})", "DIR/runs.json", 0); }).find("expected at least one run"),
            std::string::npos);
  EXPECT_NE(InputErrorOf([&] { RunsFromJson("[", "DIR/runs.json", 0); }).find("DIR/runs.json: invalid JSON"),
            std::string::npos);
}

TEST(RunOfFrames, NumbersEachFrameWithItsRun) {
  EXPECT_EQ(RunOfFrames(ThreeRuns()), (std::vector<int>{0, 0, 0, 0, 1, 1, 1, 2, 2}));
  EXPECT_EQ(RunOfFrames(SingleRun(3)), (std::vector<int>{0, 0, 0}));
}

// A dataset of 5 frames with only what Open needs, and runs.json when given.
void WriteDataset(const std::string& dir, const std::string& runs_json) {
  DatasetManifest m;
  m.hoilcd_version = "test";
  m.scene_hash = ChecksumOf("{}");
  m.intrinsics = CameraIntrinsics::FromHorizontalFov(8, 6, 50);
  m.frame_count = 5;
  m.outputs.radiometric = m.outputs.exr = m.outputs.video = m.outputs.persons = false;
  WriteDatasetFile(dir, "scene.json", "{}\n", &m);
  std::vector<PoseRecord> poses(5);
  for (int f = 0; f < 5; ++f) {
    poses[f].frame = f;
    poses[f].time_s = f < 3 ? f : 3600 + f;
    WriteDatasetFile(dir, "thermal/" + FrameFileName(f, "png"), EncodePng(cv::Mat(6, 8, CV_8UC1, cv::Scalar(f))), &m);
  }
  WriteDatasetFile(dir, "poses.csv", PosesToCsv(poses), &m);
  WriteDatasetFile(dir, "events.json", EventsToJson({}), &m);
  if (!runs_json.empty()) WriteDatasetFile(dir, "runs.json", runs_json, &m);
  m.complete = true;
  WriteFileAtomic(dir + "/manifest.json", m.ToJson());
}

TEST(Dataset, RunsJsonSetsEachPosesRunAndItsAbsenceIsOneRun) {
  test::TestDir dir;
  WriteDataset(dir / "one", "");
  const Dataset one = Dataset::Open(dir / "one");
  ASSERT_EQ(one.runs().size(), 1u);
  EXPECT_EQ(one.runs()[0].frames, 5);
  for (const PoseRecord& p : one.poses()) EXPECT_EQ(p.run, 0);

  WriteDataset(dir / "two", RunsToJson({{0, 3, 9, 0, 0, 1}, {3, 2, 10, 0, 3600, 2}}));
  const Dataset two = Dataset::Open(dir / "two");
  ASSERT_EQ(two.runs().size(), 2u);
  EXPECT_EQ(two.runs()[1].time_of_day_h, 10);
  std::vector<int> runs;
  for (const PoseRecord& p : two.poses()) runs.push_back(p.run);
  EXPECT_EQ(runs, (std::vector<int>{0, 0, 0, 1, 1}));

  WriteDataset(dir / "bad", RunsToJson({{0, 3, 9, 0, 0, 1}}));
  const std::string message = InputErrorOf([&] { Dataset::Open(dir / "bad"); });
  EXPECT_NE(message.find(dir / "bad/runs.json" + ": /runs: the runs end at frame 3, expected 5"), std::string::npos)
      << message;
}

}  // namespace
}  // namespace hoilcd
