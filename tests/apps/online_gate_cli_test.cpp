// Issue 45, defects 10 and 11: `bench --online` gates against --baseline and writes --junit as the
// offline bench does, and refuses by name the flags of what it does not compute; `inspect` checks
// the files it reads against manifest.json as the bench does.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hoilcd/core/util/file_io.h"
#include "run_cli.h"
#include "test_dir.h"
#include "tiny_room.h"

namespace hoilcd {
namespace {

// A report.json holding one method at MRR and R@1 `value`, of bench mode `mode` ("" : no mode key,
// as the offline bench writes).
std::string Baseline(const test::TestDir& temp, const std::string& name, const std::string& method, double value,
                     const std::string& mode) {
  nlohmann::json report = {{"methods", {{method, {{"mrr", value}, {"recall_at_1", value}}}}}};
  if (!mode.empty()) report["mode"] = mode;
  WriteFileAtomic(temp / name, report.dump());
  return temp / name;
}

TEST(OnlineBenchCli, TheGateFailsAgainstABetterBaselineAndWritesJunit) {
  const test::TestDir temp;
  const std::string dataset = test::RenderTinyRoom(temp / "dataset");
  const std::string better = Baseline(temp, "better.json", "slcd", 0.99, "online");
  const std::vector<std::string> online = {"bench", dataset, "--online", "--methods", "slcd"};

  std::vector<std::string> gated = online;
  gated.insert(gated.end(),
               {"-o", temp / "r1", "--baseline", better, "--max-drop", "0", "--junit", temp / "junit.xml"});
  const test::CliOutcome regressed = test::RunCli(gated);
  EXPECT_EQ(regressed.exit_code, 3) << regressed.err;
  EXPECT_NE(regressed.out.find("regression: method slcd, mrr old 0.9900"), std::string::npos) << regressed.out;
  const std::string junit = ReadFileBytes(temp / "junit.xml");
  EXPECT_NE(junit.find("tests=\"1\" failures=\"1\""), std::string::npos) << junit;

  // Against its own report: no regression, exit 0.
  std::vector<std::string> own = online;
  own.insert(own.end(), {"-o", temp / "r2", "--baseline", temp / "r1/report.json"});
  const test::CliOutcome same = test::RunCli(own);
  EXPECT_EQ(same.exit_code, 0) << same.err;
  EXPECT_NE(same.out.find("no headline metric dropped"), std::string::npos) << same.out;
}

TEST(OnlineBenchCli, AMissingOrOfflineBaselineIsRefusedBeforeAnyWork) {
  const test::TestDir temp;
  const std::string dataset = test::RenderTinyRoom(temp / "dataset", {"frames=12"});
  const test::CliOutcome missing = test::RunCli({"bench", dataset, "--online", "--methods", "slcd", "-o", temp / "r",
                                                 "--baseline", temp / "missing.json", "--max-drop", "0"});
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.err.find(temp / "missing.json"), std::string::npos) << missing.err;
  EXPECT_FALSE(std::filesystem::exists(temp / "r"));

  const std::string offline = Baseline(temp, "offline.json", "slcd", 0.5, "");
  const test::CliOutcome other =
      test::RunCli({"bench", dataset, "--online", "--methods", "slcd", "-o", temp / "r", "--baseline", offline});
  EXPECT_EQ(other.exit_code, 1);
  EXPECT_NE(other.err.find(offline + ": is the report of an offline bench, this is an online one"), std::string::npos)
      << other.err;
  EXPECT_FALSE(std::filesystem::exists(temp / "r"));

  // And the other way round: the offline bench refuses an online report.
  const std::string online = Baseline(temp, "online.json", "slcd", 0.5, "online");
  const test::CliOutcome back =
      test::RunCli({"bench", dataset, "--methods", "slcd", "-o", temp / "r", "--baseline", online});
  EXPECT_EQ(back.exit_code, 1);
  EXPECT_NE(back.err.find(online + ": is the report of an online bench, this is an offline one"), std::string::npos)
      << back.err;
}

TEST(OnlineBenchCli, RefusesTheFlagsOfWhatItDoesNotComputeByNameBeforeAnyWork) {
  const test::TestDir temp;
  const std::string dataset = test::RenderTinyRoom(temp / "dataset", {"frames=12"});
  // What is given, and the flag the error names.
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--dump-scores", temp / "scores"}, "--dump-scores"},
      {{"--slam"}, "--slam"},
      {{"--no-slam"}, "--slam"},
      {{"--slam-backend", "dcs"}, "--slam-backend"},
      {{"--loop-threshold", "5"}, "--loop-threshold"},
      {{"--strata", "lap"}, "--strata"},
      {{"--shortlist-index", "flat", "--shortlist-search-depth", "8"}, "--shortlist-search-depth"}};
  for (const auto& [given, flag] : cases) {
    std::vector<std::string> args = {"bench", dataset, "--online", "--methods", "slcd", "-o", temp / "r"};
    args.insert(args.end(), given.begin(), given.end());
    const test::CliOutcome o = test::RunCli(args);
    EXPECT_EQ(o.exit_code, 1) << flag;
    EXPECT_EQ(o.err.rfind("error: " + flag + ": ", 0), 0u) << o.err;
    EXPECT_FALSE(std::filesystem::exists(temp / "r")) << flag;
    EXPECT_FALSE(std::filesystem::exists(temp / "scores")) << flag;
  }
}

TEST(InspectCli, APosesCsvThatFailsItsChecksumIsRefusedNamingIt) {
  const test::TestDir temp;
  const std::string dataset = test::RenderTinyRoom(temp / "dataset", {"frames=12"});
  const test::CliOutcome before = test::RunCli({"inspect", dataset, "--json"});
  ASSERT_EQ(before.exit_code, 0) << before.err;
  std::string poses = ReadFileBytes(dataset + "/poses.csv");
  const size_t digit = poses.find_first_of("123456789", poses.find('\n') + 1);
  poses[digit] = poses[digit] == '9' ? '8' : static_cast<char>(poses[digit] + 1);
  WriteFileAtomic(dataset + "/poses.csv", poses);
  const test::CliOutcome after = test::RunCli({"inspect", dataset, "--json", "-o", temp / "checks"});
  EXPECT_EQ(after.exit_code, 1) << after.out;
  EXPECT_NE(after.err.find("error: " + dataset + "/poses.csv: checksum mismatch"), std::string::npos) << after.err;
  EXPECT_EQ(after.out, "");
  EXPECT_FALSE(std::filesystem::exists(temp / "checks/inspect.json"));
}

}  // namespace
}  // namespace hoilcd
