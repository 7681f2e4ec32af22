#include "hoilcd/bench/runner.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "hoilcd/bench/methods.h"
#include "hoilcd/bench/report.h"
#include "hoilcd/sim/sequence.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

// Renders the tiny test room once per variant into a temp folder and opens it.
Dataset TinyDataset(const std::string& name, const std::vector<std::string>& overrides = {}) {
  const fs::path dir = fs::temp_directory_path() / ("hoilcd_runner_test_" + name);
  fs::remove_all(dir);
  const Scene scene = LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/tests/data/tiny_room.json", overrides);
  SequenceOptions options;
  options.output_dir = dir.string();
  RenderSequence(scene, options);
  return Dataset::Open(dir.string());
}

TEST(Runner, EveryMethodIsScoredOnEveryQueryAndResultsDoNotDependOnThreads) {
  const Dataset dataset = TinyDataset("people");
  BenchOptions options;
  options.methods = DefaultMethods();
  options.threads = 1;
  const BenchResult one = RunBench(dataset, options);
  options.threads = 2;
  const BenchResult two = RunBench(dataset, options);
  ASSERT_EQ(one.runs.size(), DefaultMethods().size());
  ASSERT_FALSE(one.queries.empty());
  for (size_t m = 0; m < one.runs.size(); ++m) {
    const MethodRun& a = one.runs[m];
    EXPECT_EQ(a.name, DefaultMethods()[m]);
    EXPECT_GT(a.metrics.queries_scored, 0) << a.name;
    EXPECT_GE(a.metrics.mrr, 0.0) << a.name;
    EXPECT_LE(a.metrics.mrr, 1.0) << a.name;
    EXPECT_EQ(a.scores, two.runs[m].scores) << a.name;
  }
  EXPECT_GT(one.mean_hoi_points_per_frame, 0.0);
  EXPECT_TRUE(one.tracking_evaluated);
  // A method that sees the room beats chance: thumbnails of a static room recover places.
  EXPECT_GT(one.Find("thumb")->metrics.mrr, 0.3);
}

TEST(Runner, EmptyRoomGivesDlcdNothingAndTheReportSaysSo) {
  const Dataset dataset = TinyDataset("empty", {"crowd.people_per_table=0"});
  BenchOptions options;
  options.methods = ParseMethodList("paper");
  const BenchResult result = RunBench(dataset, options);
  EXPECT_EQ(result.mean_hoi_points_per_frame, 0.0);
  for (const auto& scores : result.Find("dlcd")->scores) {
    for (double s : scores) EXPECT_EQ(s, 0.0);
  }
  EXPECT_NE(PaperFindingSummary(result).find("no HOI points"), std::string::npos);
  const std::string report = (fs::temp_directory_path() / "hoilcd_runner_test_report").string();
  fs::remove_all(report);
  WriteReport(result, dataset, options, ReportTiming{}, report);
  for (const char* file : {"report.json", "queries.csv", "report.md", "pr_curves.png", "mrr_per_lap.png",
                           "trajectory_fusion.png"}) {
    EXPECT_TRUE(fs::exists(report + "/" + file)) << file;
  }
  EXPECT_NE(ReadFileBytes(report + "/report.md").find("no HOI points"), std::string::npos);
  const nlohmann::json json = nlohmann::json::parse(ReadFileBytes(report + "/report.json"));
  for (const char* key : {"mrr", "recall_at_1", "recall_at_5", "recall_at_10", "pr_auc", "recall_at_100p",
                          "ms_per_query", "queries_scored", "queries_skipped"}) {
    EXPECT_TRUE(json["methods"]["dlcd"].contains(key)) << key;
  }
  EXPECT_TRUE(json["timing"].contains("render_s"));
  EXPECT_TRUE(json["timing"].contains("bench_s"));
}

TEST(Runner, UnknownMethodsAreInputErrorsNamingThem) {
  try {
    ParseMethodList("slcd,superglue");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.problems().at(0).where, "--methods");
    EXPECT_NE(std::string(e.what()).find("superglue"), std::string::npos);
  }
  EXPECT_EQ(ParseMethodList("paper"), (std::vector<std::string>{"slcd", "dlcd", "fusion"}));
}

}  // namespace
}  // namespace hoilcd

namespace hoilcd {
namespace {

TEST(Runner, ASequenceShorterThanALapHasNoScoredQueriesAndStillReports) {
  const Dataset dataset = TinyDataset("short", {"frames=60"});
  BenchOptions options;
  options.methods = ParseMethodList("paper");
  const BenchResult result = RunBench(dataset, options);
  EXPECT_EQ(result.Find("slcd")->metrics.queries_scored, 0);
  const std::string report = (fs::temp_directory_path() / "hoilcd_runner_test_short_report").string();
  fs::remove_all(report);
  EXPECT_NO_THROW(WriteReport(result, dataset, options, ReportTiming{}, report));
  EXPECT_TRUE(fs::exists(report + "/report.md"));
  EXPECT_FALSE(fs::exists(report + "/mrr_per_lap.png"));
}

}  // namespace
}  // namespace hoilcd
