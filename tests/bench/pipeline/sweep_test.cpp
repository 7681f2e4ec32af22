#include "hoilcd/bench/pipeline/sweep.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include <gtest/gtest.h>
#include <unistd.h>

#include "hoilcd/bench/pipeline/sweep_summary.h"
#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/util/error.h"
#include "input_error_of.h"
#include "option_properties.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

using test::InputErrorOf;

TEST(SweepValues, SplitOnlyOnTopLevelCommas) {
  EXPECT_EQ(SplitTopLevelCommas("0,1, 2", "--set"), (std::vector<std::string>{"0", "1", "2"}));
  EXPECT_EQ(SplitTopLevelCommas("[1,2],[3,[4,5]]", "--set"), (std::vector<std::string>{"[1,2]", "[3,[4,5]]"}));
  EXPECT_EQ(SplitTopLevelCommas(R"({"a":1,"b":[2,3]},"x,y",7)", "--set"),
            (std::vector<std::string>{R"({"a":1,"b":[2,3]})", R"("x,y")", "7"}));
  EXPECT_EQ(SplitTopLevelCommas("single", "--set"), (std::vector<std::string>{"single"}));
}

TEST(SweepValues, AxisValuesAreCanonicalJsonSoSpacingDoesNotNameANewRun) {
  const SweepAxis axis = ParseSweepAxis("tables.0.center_m=[1, 2], [3,4]");
  EXPECT_EQ(axis.key, "tables.0.center_m");
  EXPECT_EQ(axis.values, (std::vector<std::string>{"[1,2]", "[3,4]"}));
}

TEST(SweepValues, BadSetSyntaxIsAnErrorNamingTheFlag) {
  for (const std::string bad :
       {"crowd.people_per_table", "=1,2", "crowd.people_per_table=1,,2", "crowd.people_per_table=1,", "k=[1,2", "k=1]",
        "k=\"open", "seed=1,2", "crowd.people_per_table=1,1"}) {
    const std::string message = InputErrorOf([&] { ParseSweepAxis(bad); });
    EXPECT_NE(message.find("--set"), std::string::npos) << bad << " gave: " << message;
  }
}

TEST(SweepOptions, HoldTheirTablesDefaultsAndNameAMissingFolderABadShardAndABadRun) {
  SweepOptions options;
  EXPECT_EQ(options.run.cache_dir, "runs");
  EXPECT_EQ(options.Check(), "output_dir: the output folder must be given");
  options.output_dir = "out";
  EXPECT_EQ(options.Check(), "");
  EXPECT_EQ(ExpectEveryBoundCrossedIsNamedByCheck<SweepOptions>(), 1);  // run/threads
  options.shard.index = 2;
  options.shard.count = 2;
  EXPECT_EQ(options.Check(), "shard: the shard index must be in 0..1");
  options.shard = Shard();
  options.run.cache_dir = "";
  EXPECT_EQ(options.Check(), "run/cache_dir: must not be empty");
}

// Eleven switches of the thermal effects in one run: the full name is over 255 bytes, which no
// file system takes as a folder name, so the folder keeps a prefix and a hash of the whole name.
TEST(SweepRunSpec, ALongRunNameGetsAShortDistinctFolderAndAShortOneKeepsItsName) {
  SweepRunSpec a, b, short_run;
  for (const char* key :
       {"crowd.garments.enabled", "crowd.garments.skin_pattern", "crowd.contact_heat.enabled",
        "room.surfaces.thermal_bridges", "room.surfaces.radiator_plume", "room.surfaces.glass_from_u_value",
        "room.surfaces.window_frames", "room.surfaces.texture", "room.hvac.enabled", "room.sun.enabled"}) {
    a.settings.emplace_back(key, "false");
    b.settings.emplace_back(key, "false");
  }
  a.settings.emplace_back("camera.specular_reflections", "false");
  b.settings.emplace_back("camera.specular_reflections", "true");
  a.seed = b.seed = 1;
  ASSERT_GT(a.Name().size(), 255u);
  EXPECT_EQ(a.FolderName().size(), SweepRunSpec::kMaxFolderName);
  EXPECT_EQ(a.FolderName().substr(0, 40), a.Name().substr(0, 40));
  EXPECT_NE(a.FolderName(), b.FolderName());  // they differ only beyond the kept prefix
  EXPECT_EQ(a.FolderName(), a.FolderName());
  short_run.settings.emplace_back("crowd.people_per_table", "2");
  short_run.seed = 3;
  EXPECT_EQ(short_run.FolderName(), "crowd.people_per_table=2,seed=3");
}

TEST(SweepPlanRuns, ShardsPartitionTheCrossProduct) {
  SweepPlan plan;
  plan.scene_path = "scene.json";
  plan.axes = {{"a", {"0", "1", "2"}}, {"b", {"[1,2]", "x"}}};
  plan.seeds = 3;
  const std::vector<SweepRunSpec> all = plan.Runs();
  ASSERT_EQ(all.size(), 18u);
  std::set<std::string> names;
  for (const SweepRunSpec& r : all) names.insert(r.Name());
  EXPECT_EQ(names.size(), 18u);
  EXPECT_TRUE(names.count("a=1,b=[1,2],seed=3"));
  std::multiset<std::string> from_shards;
  for (int i = 0; i < 4; ++i) {
    for (const SweepRunSpec& r : plan.ShardRuns({i, 4})) from_shards.insert(r.Name());
  }
  EXPECT_EQ(from_shards, std::multiset<std::string>(names.begin(), names.end()));
  EXPECT_EQ(plan.ShardRuns({0, 4}).size(), 5u);
  EXPECT_EQ(plan.ShardRuns({3, 4}).size(), 4u);
}

TEST(SweepPlanJson, AScenePathThatIsNotUtf8IsWrittenEscaped) {
  SweepPlan plan;
  plan.scene_path = "sc\xe9ne.json";  // Latin-1
  plan.axes = {{"a", {"0"}}};
  std::string text;
  ASSERT_NO_THROW(text = plan.ToJson().dump());
  EXPECT_NE(text.find("\"scene_path\":\"sc\\\\xe9ne.json\""), std::string::npos) << text;
}

TEST(SweepStatsOf, MeanSampleStdMinMaxOfFiniteValues) {
  const SweepStats s = SweepStats::Of({1.0, 3.0, NAN, 2.0});
  EXPECT_EQ(s.count, 3);
  EXPECT_DOUBLE_EQ(s.mean, 2.0);
  EXPECT_DOUBLE_EQ(s.std, 1.0);
  EXPECT_DOUBLE_EQ(s.min, 1.0);
  EXPECT_DOUBLE_EQ(s.max, 3.0);
  EXPECT_DOUBLE_EQ(SweepStats::Of({0.5}).std, 0.0);
  EXPECT_TRUE(std::isnan(SweepStats::Of({NAN}).mean));
}

// A small room with one table ahead of a small loop, 64x48 px: one lap takes ~110 frames.
std::string WriteTinyScene(const fs::path& dir) {
  fs::create_directories(dir);
  const std::string path = (dir / "tiny.json").string();
  std::ofstream(path) << R"({
    "name": "sweep_tiny",
    "seed": 1,
    "frames": 200,
    "room": {"size_m": [4.0, 3.0, 2.6]},
    "tables": [{"center_m": [2.9, 1.5], "yaw_deg": 0}],
    "objects": [],
    "crowd": {"people_per_table": 2},
    "camera": {"width_px": 64, "height_px": 48},
    "route": {"waypoints_m": [[0.8, 1.25], [0.8, 1.75], [1.6, 1.75], [1.6, 1.25]],
              "corner_radius_m": 0.2, "max_lateral_accel_m_s2": 1.0}
  })";
  return path;
}

class SweepEndToEnd : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // One folder per process: ctest may run other test processes at the same time.
    root_ = new fs::path(fs::temp_directory_path() / ("hoilcd_sweep_test_" + std::to_string(::getpid())));
    fs::remove_all(*root_);
    bench_ = new BenchOptions();
    bench_->methods = {"slcd", "dlcd", "fusion"};
    bench_->protocol.exclusion_window_s = 2;  // the loop takes ~5 s
    plan_ = new SweepPlan(MakeSweepPlan(WriteTinyScene(*root_), {"crowd.people_per_table=0,1"}, 2, *bench_));
    SweepOptions options;
    options.run.cache_dir = (*root_ / "cache").string();
    options.run.threads = 2;
    options.output_dir = Dir("whole");
    RunSweep(*plan_, *bench_, options);
    for (int i = 0; i < 2; ++i) {
      options.shard = {i, 2};
      options.output_dir = Dir("shard" + std::to_string(i));
      RunSweep(*plan_, *bench_, options);
    }
    setup_done_ = true;
  }
  // A failure inside SetUpTestSuite makes GoogleTest skip the tests; this turns it into failures.
  void SetUp() override { ASSERT_TRUE(setup_done_) << "the sweeps of SetUpTestSuite failed"; }
  static void TearDownTestSuite() {
    fs::remove_all(*root_);
    delete plan_;
    delete bench_;
    delete root_;
  }
  static std::string Dir(const std::string& name) { return (*root_ / name).string(); }

  static fs::path* root_;
  static BenchOptions* bench_;
  static SweepPlan* plan_;
  static bool setup_done_;
};
bool SweepEndToEnd::setup_done_ = false;
fs::path* SweepEndToEnd::root_ = nullptr;
BenchOptions* SweepEndToEnd::bench_ = nullptr;
SweepPlan* SweepEndToEnd::plan_ = nullptr;

TEST_F(SweepEndToEnd, RunsScoreQueriesAndKeepEveryReport) {
  for (const SweepRunSpec& run : plan_->Runs()) {
    const std::string report = Dir("whole") + "/runs/" + run.FolderName() + "/report.json";
    ASSERT_TRUE(fs::exists(report)) << report;
    const nlohmann::json j = nlohmann::json::parse(ReadFileBytes(report));
    EXPECT_GT(j["methods"]["slcd"]["queries_scored"].get<int>(), 10) << run.Name();
  }
  EXPECT_EQ(plan_->Runs().size(), 4u);
}

TEST_F(SweepEndToEnd, TwoShardsMergedGiveTheSameSummaryAsTheUnshardedRun) {
  const SweepSummary whole = MergeSweep({Dir("whole")}, plan_);
  const SweepSummary merged = MergeSweep({Dir("shard0"), Dir("shard1")});
  ASSERT_EQ(whole.rows.size(), 6u);  // 2 values x 3 methods
  ASSERT_EQ(merged.rows.size(), whole.rows.size());
  EXPECT_EQ(merged.plan.ToJson(), whole.plan.ToJson());
  const std::vector<SweepMetric>& metrics = SweepMetrics();
  for (size_t r = 0; r < whole.rows.size(); ++r) {
    const SweepSummaryRow& a = whole.rows[r];
    const SweepSummaryRow& b = merged.rows[r];
    EXPECT_EQ(a.settings, b.settings);
    EXPECT_EQ(a.method, b.method);
    EXPECT_EQ(a.seeds, (std::vector<int>{1, 2}));
    EXPECT_EQ(b.seeds, a.seeds);
    for (size_t k = 0; k < metrics.size(); ++k) {
      if (metrics[k].key == "ms_per_query") {
        EXPECT_TRUE(std::isfinite(b.stats[k].mean));  // measured time: differs run to run
        continue;
      }
      EXPECT_EQ(a.stats[k].count, 2) << a.method << " " << metrics[k].label;
      EXPECT_EQ(a.stats[k].mean, b.stats[k].mean) << a.method << " " << metrics[k].label;
      EXPECT_EQ(a.stats[k].std, b.stats[k].std) << a.method << " " << metrics[k].label;
      EXPECT_EQ(a.stats[k].min, b.stats[k].min) << a.method << " " << metrics[k].label;
      EXPECT_EQ(a.stats[k].max, b.stats[k].max) << a.method << " " << metrics[k].label;
    }
  }
}

TEST_F(SweepEndToEnd, SummaryFilesAndOnePlotPerMetricAreWritten) {
  const SweepSummary merged = MergeSweep({Dir("shard0"), Dir("shard1")});
  const std::string out = Dir("merged");
  WriteSweepSummary(merged, out);
  const std::string csv = ReadFileBytes(out + "/summary.csv");
  EXPECT_EQ(csv.rfind("crowd.people_per_table,method,seeds,mrr_mean,mrr_std,mrr_min,mrr_max,", 0), 0u);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 6);  // header + 2 values x 3 methods
  EXPECT_NE(ReadFileBytes(out + "/summary.md").find("| 1 | dlcd | 2 |"), std::string::npos);
  for (const SweepMetric& metric : SweepMetrics()) {
    EXPECT_TRUE(fs::exists(out + "/plot_crowd.people_per_table_" + metric.key + ".png")) << metric.key;
  }
}

TEST_F(SweepEndToEnd, SummaryJsonHoldsThePlanAndEveryRowsStatistics) {
  const SweepSummary merged = MergeSweep({Dir("shard0"), Dir("shard1")});
  const std::string out = Dir("merged_json");
  WriteSweepSummary(merged, out);
  const nlohmann::json j = nlohmann::json::parse(ReadFileBytes(out + "/summary.json"));
  EXPECT_EQ(j["plan"], merged.plan.ToJson());
  ASSERT_EQ(j["rows"].size(), merged.rows.size());
  EXPECT_EQ(j["rows"][0]["stats"]["mrr"]["mean"].get<double>(), merged.rows[0].stats[0].mean);
}

TEST_F(SweepEndToEnd, TheSummaryNeverOverwritesTheUsersFilesButReplacesItsOwn) {
  const SweepSummary merged = MergeSweep({Dir("shard0"), Dir("shard1")});
  // The cluster layout: the summary goes beside the shards' folders and logs.
  const std::string beside = Dir("cluster");
  fs::create_directories(beside + "/shard-0");
  fs::create_directories(beside + "/logs");
  WriteFileAtomic(beside + "/logs/merge.out", "log");
  EXPECT_NO_THROW(WriteSweepSummary(merged, beside));
  EXPECT_NO_THROW(WriteSweepSummary(merged, beside));  // an earlier summary (summary.json) is its own
  // A summary.md of the user's, with no sweep there: refused, named, left as it was.
  const std::string users = Dir("users_summary");
  fs::create_directories(users);
  WriteFileAtomic(users + "/summary.md", "my notes");
  const std::string message = InputErrorOf([&] { WriteSweepSummary(merged, users); });
  EXPECT_NE(message.find("summary.md"), std::string::npos) << message;
  EXPECT_EQ(ReadFileBytes(users + "/summary.md"), "my notes");
  EXPECT_FALSE(fs::exists(users + "/summary.csv"));
}

TEST_F(SweepEndToEnd, ASweepRefusesAFolderOfTheUsersBeforeAnyWork) {
  const std::string users = Dir("users_folder");
  fs::create_directories(users);
  WriteFileAtomic(users + "/summary.csv", "mine");
  SweepOptions options;
  options.run.cache_dir = Dir("cache");
  options.output_dir = users;
  const std::string message = InputErrorOf([&] { RunSweep(*plan_, *bench_, options); });
  EXPECT_NE(message.find("summary.csv"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(users + "/sweep.json"));
  EXPECT_EQ(ReadFileBytes(users + "/summary.csv"), "mine");
}

TEST_F(SweepEndToEnd, RerunKeepsEveryFinishedRunInsteadOfRunningItAgain) {
  SweepOptions options;
  options.run.cache_dir = (*root_ / "cache").string();
  options.output_dir = Dir("whole");
  int kept = 0, calls = 0;
  RunSweep(*plan_, *bench_, options, [&](int, int, const SweepRunSpec&, bool k) {
    ++calls;
    kept += k ? 1 : 0;
  });
  EXPECT_EQ(calls, 4);
  EXPECT_EQ(kept, 4);
}

TEST_F(SweepEndToEnd, MergeNamesAMissingRun) {
  const std::string message = InputErrorOf([&] { MergeSweep({Dir("shard0")}); });
  ASSERT_FALSE(message.empty());
  for (const SweepRunSpec& run : plan_->ShardRuns({1, 2})) {
    EXPECT_NE(message.find("missing run " + run.Name()), std::string::npos) << message;
  }
  for (const SweepRunSpec& run : plan_->ShardRuns({0, 2})) {
    EXPECT_EQ(message.find("missing run " + run.Name() + " "), std::string::npos) << message;
  }
}

TEST_F(SweepEndToEnd, MergeNamesADuplicatedRun) {
  const std::string message = InputErrorOf([&] { MergeSweep({Dir("shard0"), Dir("whole")}); });
  const std::string name = plan_->ShardRuns({0, 2}).front().Name();
  EXPECT_NE(message.find("run " + name + " appears 2 times"), std::string::npos) << message;
}

TEST_F(SweepEndToEnd, MergeRejectsAShardOfAnotherSweep) {
  SweepPlan other = *plan_;
  other.seeds = 3;
  const std::string message = InputErrorOf([&] { MergeSweep({Dir("shard0"), Dir("shard1")}, &other); });
  EXPECT_NE(message.find("/seeds"), std::string::npos) << message;
}

TEST(SweepPlanMaking, AValueTheSceneRejectsFailsBeforeRendering) {
  const test::TestDir temp;
  const std::string scene = WriteTinyScene(temp.path());
  const std::string message =
      InputErrorOf([&] { MakeSweepPlan(scene, {"crowd.people_per_table=0,9"}, 1, BenchOptions{}); });
  EXPECT_NE(message.find("--set"), std::string::npos) << message;
  EXPECT_NE(message.find("crowd.people_per_table=9"), std::string::npos) << message;
  EXPECT_NE(InputErrorOf([&] { MakeSweepPlan(scene, {}, 0, BenchOptions{}); }).find("--seeds"), std::string::npos);
  EXPECT_NE(InputErrorOf([&] {
              MakeSweepPlan(scene, {"crowd.people_per_table=1", "crowd.people_per_table=2"}, 1, BenchOptions{});
            }).find("--set"),
            std::string::npos);
}

TEST(SweepPlanMaking, ACrossProductBeyondAHundredThousandRunsIsRefusedByNameBeforeListingIt) {
  const test::TestDir temp;
  const std::string scene = WriteTinyScene(temp.path());
  std::string values;
  for (int v = 0; v < 1000; ++v) values += (v ? "," : "") + std::to_string(v);
  const std::string message = InputErrorOf([&] {
    MakeSweepPlan(scene, {"crowd.walkers=" + values, "frames=" + values}, 10000, BenchOptions{});
  });
  EXPECT_NE(
      message.find("--set: 1000 values of crowd.walkers x 1000 values of frames x 10000 seeds is 10000000000 runs; "
                   "at most 100000"),
      std::string::npos)
      << message;
}

}  // namespace
}  // namespace hoilcd
