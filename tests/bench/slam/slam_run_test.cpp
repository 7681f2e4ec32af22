#include "hoilcd/bench/slam/slam_run.h"

#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hoilcd/bench/report/report.h"
#include "hoilcd/bench/runner/runner.h"
#include "hoilcd/core/util/error.h"
#include "option_properties.h"
#include "test_dir.h"
#include "tiny_room.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

Dataset TinyDataset(const fs::path& dir) { return test::TinyRoomDataset((dir / "dataset").string()); }

TEST(SlamRun, BenchWithSlamReportsEveryBackEndWritesGraphAndTrajectoriesAndIgnoresThreadCount) {
  const test::TestDir temp;
  const fs::path dir = temp.path();
  const Dataset dataset = TinyDataset(dir);
  BenchOptions options;
  options.methods = {"slcd", "thumb"};
  options.slam = true;
  options.threads = 1;
  const BenchResult one = RunBench(dataset, options);
  options.threads = 2;
  const BenchResult two = RunBench(dataset, options);
  ASSERT_TRUE(one.slam_evaluated);
  EXPECT_TRUE(std::isfinite(one.slam.odometry.ate_rmse_m));
  ASSERT_EQ(one.slam.oracle.size(), PoseGraphBackends().size());
  ASSERT_EQ(one.slam.methods.size(), 2u);
  for (size_t m = 0; m < one.slam.methods.size(); ++m) {
    const MethodSlam& a = one.slam.methods[m];
    EXPECT_EQ(a.threshold_source, "test sequence");  // no calibration given to RunBench
    ASSERT_EQ(a.backends.size(), PoseGraphBackends().size());
    for (size_t b = 0; b < a.backends.size(); ++b) {
      EXPECT_TRUE(std::isfinite(a.backends[b].ate_rmse_m)) << a.method;
      EXPECT_EQ(a.backends[b].ate_rmse_m, two.slam.methods[m].backends[b].ate_rmse_m) << a.method;
      EXPECT_EQ(a.backends[b].false_loops, 0) << a.method;  // 100 % precision on this very sequence
    }
  }
  ReportTiming timing;
  WriteReport(one, dataset, options, timing, (dir / "report").string());
  const nlohmann::json report = nlohmann::json::parse(ReadFileBytes((dir / "report" / "report.json").string()));
  EXPECT_TRUE(report["slam"]["odometry"]["ate_rmse_m"].is_number());
  EXPECT_TRUE(report["slam"]["oracle"]["ate_rmse_m"].is_number());
  EXPECT_EQ(report["slam"]["oracle"]["backends"].size(), PoseGraphBackends().size());
  for (const std::string& b : PoseGraphBackends()) {
    for (const char* key : {"ate_rmse_m", "rpe_rmse_m", "loops_accepted", "false_loops"}) {
      EXPECT_TRUE(report["methods"]["slcd"]["slam"][b][key].is_number()) << b << " " << key;
    }
  }
  for (const char* file : {"slam/slcd.g2o", "slam/slcd_tum.txt", "slam/thumb_tum.txt", "slam/odometry_tum.txt",
                           "slam/groundtruth_tum.txt", "slam_trajectories.png"}) {
    EXPECT_TRUE(fs::exists(dir / "report" / file)) << file;
  }
  EXPECT_NE(ReadFileBytes((dir / "report" / "report.md").string()).find("SLAM consequence"), std::string::npos);

  // A threshold that accepts no loop leaves the odometry, and the report says so.
  options.methods = {"slcd"};
  options.slam_options.slam.loop_threshold = 1e9;
  const BenchResult none = RunBench(dataset, options);
  const MethodSlam& m = none.slam.methods.front();
  EXPECT_EQ(m.threshold_source, "--loop-threshold");
  EXPECT_TRUE(m.loops.empty());
  EXPECT_EQ(m.Headline("dcs").ate_rmse_m, none.slam.odometry.ate_rmse_m);
  ASSERT_FALSE(none.slam.notes.empty());
  EXPECT_NE(none.slam.notes.back().find("slcd: threshold 1e+09 (--loop-threshold) accepts no loop"), std::string::npos)
      << none.slam.notes.back();
  fs::remove_all(dir);
}

TEST(SlamRun, BadSlamOptionsAreInputErrorsOfTheBench) {
  BenchOptions options;
  options.slam = true;
  options.slam_options.slam.graph.backend = "gauss";
  EXPECT_NE(options.Check().find("graph/backend: must be one of: plain, cauchy, dcs (got 'gauss')"), std::string::npos)
      << options.Check();
  options.slam_options = SlamRunOptions{};
  options.slam_options.curve_points = 1;
  EXPECT_NE(options.Check().find("curve_points"), std::string::npos);
}

TEST(SlamRun, OptionsHoldTheirTablesDefaultsAndEveryBoundIsChecked) {
  EXPECT_TRUE(SlamRunOptions().calibrated_threshold.empty());
  ExpectConstructedHoldsTheTableDefaults<SlamRunOptions>();
  EXPECT_EQ(ExpectEveryBoundCrossedIsNamedByCheck<SlamRunOptions>(), 12);
}

TEST(SlamRun, PosesWithoutOdometryColumnsAreRejectedWhenTheDatasetIsRead) {
  const std::string csv = "frame,t,x,y,theta,cam_x,cam_y,cam_z,cam_yaw,cam_pitch\n0,0,1,1,0,1,1,1,0,0\n";
  try {
    PosesFromCsv(csv, "poses.csv");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("poses.csv"), std::string::npos) << e.what();
  }
}

// hoilcd run scores the methods, waits for its calibration, then adds the SLAM step: the same
// as RunBench with slam on, and the thresholds given before the SLAM step are the ones used.
TEST(SlamRun, TheSlamStepAddedAfterScoringEqualsTheBenchsOwnAndUsesThresholdsGivenBeforeIt) {
  const test::TestDir temp;
  const Dataset dataset = TinyDataset(temp.path());
  BenchOptions options;
  options.methods = {"slcd", "thumb"};
  options.slam = true;
  const BenchResult whole = RunBench(dataset, options);
  int hook_calls = 0;
  ReportTiming timing;
  const BenchResult added =
      BenchAndWriteReport(dataset, options, &timing, (temp.path() / "report").string(), [&](SlamRunOptions* slam) {
        ++hook_calls;
        slam->calibrated_threshold = {{"slcd", 0.5}};
        timing.calibration_s = 7;
      });
  EXPECT_EQ(hook_calls, 1);
  ASSERT_TRUE(added.slam_evaluated);
  ASSERT_EQ(added.slam.methods.size(), whole.slam.methods.size());
  EXPECT_EQ(added.slam.methods[0].threshold, 0.5);
  EXPECT_EQ(added.slam.methods[0].threshold_source, "calibration");
  // thumb has no calibrated threshold: as in RunBench, from the test sequence.
  EXPECT_EQ(added.slam.methods[1].threshold_source, "test sequence");
  const double t_added = added.slam.methods[1].threshold, t_whole = whole.slam.methods[1].threshold;
  EXPECT_TRUE(t_added == t_whole || (std::isnan(t_added) && std::isnan(t_whole))) << t_added << " " << t_whole;
  for (size_t b = 0; b < PoseGraphBackends().size(); ++b) {
    EXPECT_EQ(added.slam.methods[1].backends[b].ate_rmse_m, whole.slam.methods[1].backends[b].ate_rmse_m);
  }
  EXPECT_EQ(added.slam.odometry.ate_rmse_m, whole.slam.odometry.ate_rmse_m);
  const nlohmann::json report = nlohmann::json::parse(ReadFileBytes((temp.path() / "report/report.json").string()));
  EXPECT_EQ(report["timing"]["calibration_s"], 7);
}

}  // namespace
}  // namespace hoilcd
