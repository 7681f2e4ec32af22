// hoilcd suite on the command line, end to end: a tiny suite whose one sequence names a missing
// scene reports that failure, summarises the other runs and exits non-zero; a rerun keeps the
// finished runs and writes the same suite_report.json bytes.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "hoilcd/core/util/file_io.h"
#include "run_cli.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

TEST(SuiteCli, ReportsAFailedRunSummarisesTheOthersAndARerunKeepsThemWithTheSameReport) {
  const test::TestDir temp;
  const std::string tiny = std::string(HOILCD_TEST_SOURCE_DIR) + "/tests/data/tiny_room.json";
  WriteFileAtomic(temp / "suite.json", R"({
    "name": "tiny",
    "sequences": [
      {"name": "tiny", "scene": ")" + tiny + R"(", "seeds": [1, 2], "split": "dev"},
      {"name": "missing", "scene": "does_not_exist.json", "seeds": [1], "split": "test"}
    ]
  })");
  const std::vector<std::string> args = {"suite", temp / "suite.json", "-o", temp / "out", "--cache", temp / "cache",
                                         "--methods", "slcd,dlcd", "--no-slam", "--threads", "2"};
  const test::CliOutcome first = test::RunCli(args);
  EXPECT_NE(first.exit_code, 0) << first.out << first.err;
  EXPECT_NE(first.err.find("missing-seed1"), std::string::npos) << first.err;
  EXPECT_NE(first.err.find("does_not_exist.json"), std::string::npos) << first.err;
  EXPECT_NE(first.err.find("1 of 3 runs failed"), std::string::npos) << first.err;

  const std::string report_path = temp / "out/suite_report.json";
  const nlohmann::json report = nlohmann::json::parse(ReadFileBytes(report_path));
  EXPECT_EQ(report["runs"], (nlohmann::json{"tiny-seed1", "tiny-seed2"}));
  ASSERT_EQ(report["failed"].size(), 1u);
  EXPECT_EQ(report["failed"][0]["run"], "missing-seed1");
  EXPECT_NE(report["failed"][0]["error"].get<std::string>().find("does_not_exist.json"), std::string::npos);
  ASSERT_EQ(report["methods"].size(), 2u);
  for (const nlohmann::json& m : report["methods"]) {
    ASSERT_TRUE(m["mrr"]["mean"].is_number()) << m.dump();
    const double mean = m["mrr"]["mean"].get<double>();
    EXPECT_LE(m["mrr"]["interval"][0].get<double>(), mean);
    EXPECT_GE(m["mrr"]["interval"][1].get<double>(), mean);
    EXPECT_EQ(m["runs"].size(), 2u);
  }
  EXPECT_EQ(report["wins"].size(), 1u);
  EXPECT_EQ(report["settings"]["split"], "all");
  EXPECT_EQ(report["settings"]["bench"]["methods"], (nlohmann::json{"slcd", "dlcd"}));
  const std::string markdown = ReadFileBytes(temp / "out/suite_report.md");
  EXPECT_NE(markdown.find("missing-seed1"), std::string::npos) << markdown;

  const std::string bytes = ReadFileBytes(report_path);
  const auto run_report_time = fs::last_write_time(temp / "out/runs/tiny-seed1/report.json");
  const test::CliOutcome again = test::RunCli(args);
  EXPECT_NE(again.exit_code, 0);
  EXPECT_NE(again.out.find("tiny-seed1 (kept from an earlier run)"), std::string::npos) << again.out;
  EXPECT_NE(again.out.find("tiny-seed2 (kept from an earlier run)"), std::string::npos) << again.out;
  EXPECT_EQ(fs::last_write_time(temp / "out/runs/tiny-seed1/report.json"), run_report_time);
  EXPECT_EQ(ReadFileBytes(report_path), bytes);
}

TEST(SuiteCli, RefusesABadSuiteFileAFolderOfTheUsersAndAnEmptySplit) {
  const test::TestDir temp;
  WriteFileAtomic(temp / "bad.json", R"({"name": "s", "sequences": [{"name": "a", "seeds": [1], "split": "dev"}]})");
  const test::CliOutcome bad = test::RunCli({"suite", temp / "bad.json", "-o", temp / "out"});
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("bad.json: /sequences/0: expected exactly one of"), std::string::npos) << bad.err;

  WriteFileAtomic(temp / "dev.json", R"({"name": "s", "sequences": [{"name": "a", "scene": "x.json", "seeds": [1], "split": "dev"}]})");
  const test::CliOutcome empty = test::RunCli({"suite", temp / "dev.json", "-o", temp / "out", "--split", "test"});
  EXPECT_EQ(empty.exit_code, 1);
  EXPECT_NE(empty.err.find("no sequence in split test"), std::string::npos) << empty.err;

  fs::create_directories(temp / "mine");
  WriteFileAtomic(temp / "mine/notes.txt", "the user's");
  const test::CliOutcome mine = test::RunCli({"suite", temp / "dev.json", "-o", temp / "mine"});
  EXPECT_EQ(mine.exit_code, 1);
  EXPECT_NE(mine.err.find("notes.txt"), std::string::npos) << mine.err;
  EXPECT_EQ(ReadFileBytes(temp / "mine/notes.txt"), "the user's");
}

}  // namespace
}  // namespace hoilcd
