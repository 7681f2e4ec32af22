// hoilcd suite on the command line, end to end: a tiny suite whose one sequence names a missing
// scene reports that failure, summarises the other runs and exits non-zero; a rerun keeps the
// finished runs and writes the same suite_report.json bytes. Shards and their merge: the merged
// report has the unsharded bytes, and every refusal names the flag or the folder.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

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
      {"name": "tiny", "scene": ")" + tiny +
                                           R"(", "seeds": [1, 2], "split": "dev"},
      {"name": "missing", "scene": "does_not_exist.json", "seeds": [1], "split": "test"}
    ]
  })");
  const std::vector<std::string> args = {"suite",     temp / "suite.json", "-o",        temp / "out",
                                         "--cache",   temp / "cache",      "--methods", "slcd,dlcd",
                                         "--no-slam", "--threads",         "2"};
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

// Issue 45: a run's report is kept on a rerun only when everything that made it is unchanged; the
// strata and the SLAM settings were not compared, so a rerun asking for them kept the old report.
TEST(SuiteCli, ARerunWithOtherStrataOrSlamSettingsBenchesTheRunAgain) {
  const test::TestDir temp;
  const std::string tiny = std::string(HOILCD_TEST_SOURCE_DIR) + "/tests/data/tiny_room.json";
  WriteFileAtomic(temp / "suite.json", R"({"name": "tiny", "sequences": [
      {"name": "tiny", "scene": ")" + tiny +
                                           R"(", "seeds": [1], "split": "dev", "set": ["frames=30"]}]})");
  const std::vector<std::string> args = {"suite",   temp / "suite.json", "-o",        temp / "out",
                                         "--cache", temp / "cache",      "--methods", "thumb"};
  ASSERT_EQ(test::RunCli(args).exit_code, 0);
  const std::string report = temp / "out/runs/tiny-seed1/report.json";
  for (const std::vector<std::string>& changed :
       {std::vector<std::string>{"--strata", "lap"}, std::vector<std::string>{"--slam", "--loop-threshold", "5"},
        std::vector<std::string>{"--slam", "--loop-threshold", "7"},
        std::vector<std::string>{"--slam", "--loop-threshold", "7", "--slam-backend", "cauchy"}}) {
    std::vector<std::string> again = args;
    again.insert(again.end(), changed.begin(), changed.end());
    const test::CliOutcome o = test::RunCli(again);
    EXPECT_EQ(o.exit_code, 0) << o.err;
    EXPECT_EQ(o.out.find("kept from an earlier run"), std::string::npos) << changed[0] << "\n" << o.out;
    const nlohmann::json j = nlohmann::json::parse(ReadFileBytes(report));
    if (changed[0] == "--strata") {
      EXPECT_TRUE(j.contains("strata")) << j.dump().substr(0, 300);
    } else {
      ASSERT_TRUE(j.contains("slam")) << j.dump().substr(0, 300);
    }
  }
  // Unchanged settings keep it.
  std::vector<std::string> same = args;
  same.insert(same.end(), {"--slam", "--loop-threshold", "7", "--slam-backend", "cauchy"});
  EXPECT_NE(test::RunCli(same).out.find("tiny-seed1 (kept from an earlier run)"), std::string::npos);
}

TEST(SuiteCli, RefusesABadSuiteFileAFolderOfTheUsersAndAnEmptySplit) {
  const test::TestDir temp;
  WriteFileAtomic(temp / "bad.json", R"({"name": "s", "sequences": [{"name": "a", "seeds": [1], "split": "dev"}]})");
  const test::CliOutcome bad = test::RunCli({"suite", temp / "bad.json", "-o", temp / "out"});
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("bad.json: /sequences/0: expected exactly one of"), std::string::npos) << bad.err;

  WriteFileAtomic(temp / "dev.json",
                  R"({"name": "s", "sequences": [{"name": "a", "scene": "x.json", "seeds": [1], "split": "dev"}]})");
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

// Runs whose scene is missing fail at once: shards and merges of this suite render nothing.
std::string WriteFailingSuite(const test::TestDir& temp) {
  WriteFileAtomic(temp / "failing.json", R"({"name": "failing", "description": "scenes that are not there",
    "sequences": [{"name": "a", "scene": "no_a.json", "seeds": [1, 2, 3], "split": "dev"},
                  {"name": "b", "scene": "no_b.json", "seeds": [1, 2], "split": "test"}]})");
  return temp / "failing.json";
}

TEST(SuiteCli, ShardsExitZeroWithTheirFailedRunsAndMergeIntoTheUnshardedReportBytes) {
  const test::TestDir temp;
  const std::string suite = WriteFailingSuite(temp);
  const test::CliOutcome whole = test::RunCli({"suite", suite, "-o", temp / "whole", "--methods", "slcd,dlcd"});
  EXPECT_EQ(whole.exit_code, 1) << whole.err;
  std::vector<std::string> merge = {"suite", suite, "--methods", "slcd,dlcd", "--merge"};
  for (int i = 0; i < 2; ++i) {
    const std::string dir = temp / ("shard-" + std::to_string(i));
    const test::CliOutcome shard =
        test::RunCli({"suite", suite, "-o", dir, "--methods", "slcd,dlcd", "--shard", std::to_string(i) + "/2"});
    EXPECT_EQ(shard.exit_code, 0) << shard.err;
    EXPECT_NE(shard.out.find("shard " + std::to_string(i) + "/2 done"), std::string::npos) << shard.out;
    EXPECT_NE(shard.err.find("failed: a-seed"), std::string::npos) << shard.err;
    EXPECT_FALSE(fs::exists(dir + "/suite_report.json"));
    merge.push_back(dir);
  }
  merge.insert(merge.end(), {"-o", temp / "merged"});
  const test::CliOutcome merged = test::RunCli(merge);
  EXPECT_EQ(merged.exit_code, 1) << merged.err;  // as the unsharded suite: its runs failed
  EXPECT_NE(merged.err.find("error: 5 of 5 runs failed"), std::string::npos) << merged.err;
  for (const char* file : {"/suite_report.json", "/suite_report.md"}) {
    EXPECT_EQ(ReadFileBytes(temp / "merged" + file), ReadFileBytes(temp / "whole" + file)) << file;
  }
}

TEST(SuiteCli, RefusesABadShardAShardWithAMergeAndAMissingSuite) {
  const test::TestDir temp;
  const std::string suite = WriteFailingSuite(temp);
  for (const std::string bad : {"3/2", "x", ""}) {  // issue 45, defect 13: '' ran the whole suite
    const test::CliOutcome outcome = test::RunCli({"suite", suite, "-o", temp / "out", "--shard", bad});
    EXPECT_EQ(outcome.exit_code, 1) << bad;
    EXPECT_NE(outcome.err.find("--shard: "), std::string::npos) << outcome.err;
    EXPECT_NE(outcome.err.find("'" + bad + "'"), std::string::npos) << outcome.err;
    EXPECT_FALSE(fs::exists(temp / "out")) << bad;
  }
  const test::CliOutcome both = test::RunCli({"suite", "--shard", "0/2", "--merge", temp / "a", "-o", temp / "out"});
  EXPECT_EQ(both.exit_code, 1);
  EXPECT_NE(both.err.find("--shard: cannot be combined with --merge"), std::string::npos) << both.err;
  const test::CliOutcome none = test::RunCli({"suite", "-o", temp / "out"});
  EXPECT_EQ(none.exit_code, 1);
  EXPECT_NE(none.err.find("a SUITE file is needed"), std::string::npos) << none.err;
}

TEST(SuiteCli, AMergeRefusesMissingRepeatedAndForeignShardsAndAnUnfinishedRunNamingTheFolder) {
  const test::TestDir temp;
  const std::string suite = WriteFailingSuite(temp);
  std::vector<std::string> shards;
  for (int i = 0; i < 3; ++i) {
    shards.push_back(temp / ("shard-" + std::to_string(i)));
    ASSERT_EQ(test::RunCli({"suite", suite, "-o", shards.back(), "--shard", std::to_string(i) + "/3"}).exit_code, 0);
  }
  const auto merge = [&](const std::vector<std::string>& dirs, const std::vector<std::string>& flags = {}) {
    std::vector<std::string> args = {"suite"};
    args.insert(args.end(), flags.begin(), flags.end());
    args.push_back("--merge");
    args.insert(args.end(), dirs.begin(), dirs.end());
    args.insert(args.end(), {"-o", temp / "merged"});
    const test::CliOutcome outcome = test::RunCli(args);
    EXPECT_EQ(outcome.exit_code, 1);
    return outcome.err;
  };
  const std::string missing = merge({shards[0], shards[2]});
  EXPECT_NE(missing.find("--merge: shard 1/3 is missing (its runs: a-seed2, b-seed2)"), std::string::npos) << missing;
  const std::string repeated = merge({shards[0], shards[1], shards[1], shards[2]});
  EXPECT_NE(repeated.find(shards[1] + ": is shard 1/3, as " + shards[1] + " is"), std::string::npos) << repeated;
  const std::string foreign = merge(shards, {suite, "--split", "dev"});
  EXPECT_NE(foreign.find(shards[0] + ": ran another suite than the suite file and flags given to the merge: /split is "
                                     "\"dev\" there and \"all\" here"),
            std::string::npos)
      << foreign;
  const test::CliOutcome dev = test::RunCli({"suite", suite, "-o", temp / "dev", "--split", "dev", "--shard", "1/3"});
  ASSERT_EQ(dev.exit_code, 0) << dev.err;
  const std::string mixed = merge({shards[0], temp / "dev", shards[2]});
  EXPECT_NE(mixed.find(temp / "dev" + ": ran another suite than " + shards[0] + "/suite.json"), std::string::npos)
      << mixed;
  const std::string no_suite = merge({shards[0], temp / "nowhere", shards[2]});
  EXPECT_NE(no_suite.find(temp / "nowhere" + ": holds no suite"), std::string::npos) << no_suite;

  // Shard 1 as a job killed before its last run: suite.json written at the start and never again.
  nlohmann::json marker = nlohmann::json::parse(ReadFileBytes(shards[1] + "/suite.json"));
  marker["failed"].erase(marker["failed"].size() - 1);
  marker["finished"] = false;
  WriteFileAtomic(shards[1] + "/suite.json", marker.dump(2));
  const std::string unfinished = merge(shards);
  EXPECT_NE(unfinished.find(shards[1] + ": shard 1/3 has no finished run b-seed2"), std::string::npos) << unfinished;
  EXPECT_NE(unfinished.find("the shard did not finish: run it again"), std::string::npos) << unfinished;
  EXPECT_FALSE(fs::exists(temp / "merged/suite_report.json"));
  // Run again alone, it records its runs and the merge goes through (exit 1: the runs failed).
  ASSERT_EQ(test::RunCli({"suite", suite, "-o", shards[1], "--shard", "1/3"}).exit_code, 0);
  merge(shards);
  EXPECT_TRUE(fs::exists(temp / "merged/suite_report.json"));
}

}  // namespace
}  // namespace hoilcd
