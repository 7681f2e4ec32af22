// A suite run whole and in 2 and 3 shards (a tiny room at 64 x 48 px, three methods, one run
// failing on a missing scene): the shards merged write the unsharded suite_report.json and .md
// byte for byte; a merge refuses a missing, repeated or foreign shard and a run neither finished
// nor failed, naming the folder; a shard stopped early is run again alone and then merges.
#include "hoilcd/bench/pipeline/suite_report.h"

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hoilcd/bench/pipeline/suite.h"
#include "hoilcd/core/util/file_io.h"
#include "input_error_of.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;
using test::InputErrorOf;

class SuiteShards : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = new test::TestDir("suite_shards");
    const std::string tiny = std::string(HOILCD_TEST_SOURCE_DIR) + "/tests/data/tiny_room.json";
    const std::string small = R"("set": ["camera.width_px=64", "camera.height_px=48")";
    WriteFileAtomic(Dir("suite.json"), R"({
      "name": "shards",
      "description": "a tiny room on four seeds, and a missing scene",
      "sequences": [
        {"name": "tiny", "scene": ")" + tiny +
                                           R"(", "seeds": [1, 2, 3], )" + small + R"(], "split": "dev"},
        {"name": "pairs", "scene": ")" + tiny +
                                           R"(", "seeds": [4], )" + small + R"(, "crowd.people_per_table=2"],
         "split": "test"},
        {"name": "missing", "scene": "does_not_exist.json", "seeds": [1], "split": "test"}
      ]
    })");
    suite_ = new Suite(ReadSuite(Dir("suite.json")));
    bench_ = new BenchOptions();
    bench_->methods = {"slcd", "dlcd", "fusion"};
    Run("whole", Shard{});
    WriteSuiteReport(MergeSuite({Dir("whole")}), Dir("whole"));
    for (int count : {2, 3}) {
      for (int index = 0; index < count; ++index) Run(ShardDir(index, count), Shard{index, count});
    }
    setup_done_ = true;
  }
  // A failure inside SetUpTestSuite makes GoogleTest skip the tests; this turns it into failures.
  void SetUp() override { ASSERT_TRUE(setup_done_) << "the suites of SetUpTestSuite failed"; }
  static void TearDownTestSuite() {
    delete bench_;
    delete suite_;
    delete root_;
  }

  static std::string Dir(const std::string& name) { return *root_ / name; }
  static std::string ShardDir(int index, int count) {
    return "shard" + std::to_string(index) + "of" + std::to_string(count);
  }
  // Runs the shard into Dir(name); returns how many of its runs were kept from an earlier run.
  static int Run(const std::string& name, const Shard& shard) {
    SuiteOptions options;
    options.output_dir = Dir(name);
    options.shard = shard;
    options.run.cache_dir = Dir("cache");  // shared, as on a cluster: each scene renders once
    options.run.threads = 2;
    int kept = 0;
    RunSuite(*suite_, *bench_, options, [&](int, int, const SuiteRunSpec&, bool k) { kept += k ? 1 : 0; });
    return kept;
  }
  static std::vector<std::string> Shards(int count) {
    std::vector<std::string> dirs;
    for (int index = 0; index < count; ++index) dirs.push_back(Dir(ShardDir(index, count)));
    return dirs;
  }
  // Merges `dirs` into Dir(out) and expects the whole suite's report files, byte for byte.
  static void ExpectTheWholeSuitesReport(const std::vector<std::string>& dirs, const std::string& out) {
    WriteSuiteReport(MergeSuite(dirs), Dir(out));
    for (const char* file : {"/suite_report.json", "/suite_report.md"}) {
      EXPECT_EQ(ReadFileBytes(Dir(out) + file), ReadFileBytes(Dir("whole") + file)) << file;
    }
    // The page links each finished run's report.html in the shard that ran it.
    const std::string html = ReadFileBytes(Dir(out) + "/suite_report.html");
    for (const std::string& dir : dirs) {
      const std::string link = std::filesystem::path(dir).filename().string() + "/runs/tiny-seed1/report.html";
      if (std::filesystem::exists(dir + "/runs/tiny-seed1/report.html")) {
        EXPECT_NE(html.find("<a href=\"../" + link + "\">"), std::string::npos) << link;
      }
    }
  }

  static test::TestDir* root_;
  static Suite* suite_;
  static BenchOptions* bench_;
  static bool setup_done_;
};
test::TestDir* SuiteShards::root_ = nullptr;
Suite* SuiteShards::suite_ = nullptr;
BenchOptions* SuiteShards::bench_ = nullptr;
bool SuiteShards::setup_done_ = false;

TEST_F(SuiteShards, TheWholeReportScoresEveryFinishedRunAndListsTheFailedOne) {
  const nlohmann::json report = nlohmann::json::parse(ReadFileBytes(Dir("whole/suite_report.json")));
  const std::string html = ReadFileBytes(Dir("whole/suite_report.html"));
  EXPECT_NE(html.find("<a href=\"runs/tiny-seed1/report.html\">"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(Dir("whole/runs/tiny-seed1/report.html")));
  EXPECT_EQ(report["runs"], (nlohmann::json{"pairs-seed4", "tiny-seed1", "tiny-seed2", "tiny-seed3"}));
  ASSERT_EQ(report["failed"].size(), 1u);
  EXPECT_EQ(report["failed"][0]["run"], "missing-seed1");
  ASSERT_EQ(report["methods"].size(), 3u);
  for (const nlohmann::json& m : report["methods"]) EXPECT_TRUE(m["mrr"]["mean"].is_number()) << m.dump();
}

TEST_F(SuiteShards, TwoShardsMergedWriteTheUnshardedReportByteForByte) {
  ExpectTheWholeSuitesReport(Shards(2), "merged2");
}

TEST_F(SuiteShards, ThreeShardsMergedInAnyOrderWriteTheUnshardedReportByteForByte) {
  const std::vector<std::string> dirs = Shards(3);
  ExpectTheWholeSuitesReport({dirs[2], dirs[0], dirs[1]}, "merged3");
}

TEST_F(SuiteShards, EachShardRecordsItselfItsRunsAndTheSuitesIdentity) {
  const nlohmann::json marker = nlohmann::json::parse(ReadFileBytes(Dir(ShardDir(1, 3)) + "/suite.json"));
  EXPECT_EQ(marker["shard"], (nlohmann::json{{"index", 1}, {"count", 3}}));
  // Every third of missing-seed1, pairs-seed4, tiny-seed1, tiny-seed2, tiny-seed3 from the second.
  EXPECT_EQ(marker["runs"], (nlohmann::json{"pairs-seed4", "tiny-seed3"}));
  EXPECT_EQ(marker["finished"], true);
  const nlohmann::json identity = SuiteIdentity(*suite_, "all", BenchSettingsJson(*bench_));
  EXPECT_EQ(marker["identity"], identity);
  EXPECT_EQ(marker["identity_hash"], ChecksumOf(identity.dump()));
  const nlohmann::json first = nlohmann::json::parse(ReadFileBytes(Dir(ShardDir(0, 3)) + "/suite.json"));
  ASSERT_EQ(first["failed"].size(), 1u);
  EXPECT_EQ(first["failed"][0]["run"], "missing-seed1");
  EXPECT_FALSE(fs::exists(Dir(ShardDir(0, 3)) + "/suite_report.json"));  // a shard writes no report
}

TEST_F(SuiteShards, AMergeChecksTheShardsAgainstTheSuiteFileAndFlagsWhenGiven) {
  const nlohmann::json same = SuiteIdentity(*suite_, "all", BenchSettingsJson(*bench_));
  EXPECT_NO_THROW(MergeSuite(Shards(2), &same));
  const nlohmann::json dev = SuiteIdentity(*suite_, "dev", BenchSettingsJson(*bench_));
  const std::string message = InputErrorOf([&] { MergeSuite(Shards(2), &dev); });
  EXPECT_NE(message.find(Dir(ShardDir(0, 2)) + ": ran another suite"), std::string::npos) << message;
  EXPECT_NE(message.find("/split is \"dev\" there and \"all\" here"), std::string::npos) << message;
  BenchOptions other = *bench_;
  other.methods = {"slcd", "dlcd"};
  const nlohmann::json methods = SuiteIdentity(*suite_, "all", BenchSettingsJson(other));
  const std::string other_methods = InputErrorOf([&] { MergeSuite(Shards(2), &methods); });
  EXPECT_NE(other_methods.find("/bench/methods is [\"slcd\",\"dlcd\"] there"), std::string::npos) << other_methods;
}

TEST_F(SuiteShards, AMergeNamesAMissingShardAndItsRuns) {
  const std::string message = InputErrorOf([&] { MergeSuite({Dir(ShardDir(0, 3)), Dir(ShardDir(2, 3))}); });
  EXPECT_NE(message.find("shard 1/3 is missing (its runs: pairs-seed4, tiny-seed3)"), std::string::npos) << message;
}

TEST_F(SuiteShards, AMergeNamesARepeatedShardAndShardsOfAnotherSplitting) {
  const std::string twice = InputErrorOf([&] {
    MergeSuite({Dir(ShardDir(0, 2)), Dir(ShardDir(1, 2)), Dir(ShardDir(0, 2))});
  });
  EXPECT_NE(twice.find(Dir(ShardDir(0, 2)) + ": is shard 0/2, as " + Dir(ShardDir(0, 2)) + " is"), std::string::npos)
      << twice;
  const std::string mixed = InputErrorOf([&] { MergeSuite({Dir(ShardDir(0, 2)), Dir(ShardDir(1, 3))}); });
  EXPECT_NE(mixed.find(Dir(ShardDir(1, 3)) + ": is shard 1/3 but"), std::string::npos) << mixed;
}

TEST_F(SuiteShards, AMergeNamesAFolderThatHoldsNoSuite) {
  const std::string message = InputErrorOf([&] { MergeSuite({Dir(ShardDir(0, 2)), Dir("cache")}); });
  EXPECT_NE(message.find(Dir("cache") + ": holds no suite"), std::string::npos) << message;
}

TEST_F(SuiteShards, AShardStoppedEarlyIsRefusedThenRunAgainAloneAndMerged) {
  // Shard 1/2 as a killed job leaves it: its suite.json written at the start, one run unfinished.
  const std::string stopped = Dir("stopped1of2");
  fs::copy(Dir(ShardDir(1, 2)), stopped, fs::copy_options::recursive);
  nlohmann::json marker = nlohmann::json::parse(ReadFileBytes(stopped + "/suite.json"));
  const std::string unfinished = marker["runs"].back().get<std::string>();
  marker["finished"] = false;
  WriteFileAtomic(stopped + "/suite.json", marker.dump(2));
  fs::remove(stopped + "/runs/" + unfinished + "/suite_run.json");
  const std::string message = InputErrorOf([&] { MergeSuite({Dir(ShardDir(0, 2)), stopped}); });
  EXPECT_NE(message.find(stopped + ": shard 1/2 has no finished run " + unfinished), std::string::npos) << message;
  EXPECT_NE(message.find("the shard did not finish"), std::string::npos) << message;

  const size_t runs = marker["runs"].size();
  EXPECT_EQ(Run("stopped1of2", Shard{1, 2}), static_cast<int>(runs) - 1 - static_cast<int>(marker["failed"].size()));
  ExpectTheWholeSuitesReport({Dir(ShardDir(0, 2)), stopped}, "merged_after_rerun");
}

TEST_F(SuiteShards, AMergeNamesEveryWayAShardFolderCanBeDamaged) {
  struct Damage {
    std::function<void(nlohmann::json* marker, const std::string& run_dir)> apply;
    std::string expected;  // part of the message, after the damaged copy's path
  };
  const auto record = [](const std::string& run_dir) {
    return nlohmann::json::parse(ReadFileBytes(run_dir + "/suite_run.json"));
  };
  const std::vector<Damage> damages = {
      {[](nlohmann::json* m, const std::string&) { m->erase("identity"); }, "suite.json: has no \"identity\""},
      {[](nlohmann::json* m, const std::string&) { (*m)["identity"] = 3; },
       "suite.json: /identity: expected an object"},
      {[](nlohmann::json* m, const std::string&) { (*m)["shard"]["index"] = 2; },
       "suite.json: /shard: the shard index must be in 0..1"},
      {[](nlohmann::json* m, const std::string&) { (*m)["shard"]["index"] = "x"; }, "suite.json: malformed suite.json"},
      {[](nlohmann::json* m, const std::string&) { (*m)["runs"].erase(0); },
       "suite.json: its runs (tiny-seed2) are not shard 1/2 of the suite's (pairs-seed4, tiny-seed2)"},
      {[&](nlohmann::json*, const std::string& dir) {
         nlohmann::json r = record(dir);
         r["seed"] = 7;
         WriteFileAtomic(dir + "/suite_run.json", r.dump());
       },
       ": shard 1/2 has no finished run tiny-seed2 (" + Dir("damaged") +
           "/runs/tiny-seed2/suite_run.json records another run)"},
      {[&](nlohmann::json*, const std::string& dir) {
         nlohmann::json r = record(dir);
         r["bench"]["methods"] = {"slcd"};
         WriteFileAtomic(dir + "/suite_run.json", r.dump());
       },
       "suite_run.json records other bench settings (at /methods/"},
      {[](nlohmann::json*, const std::string& dir) { WriteFileAtomic(dir + "/suite_run.json", "{"); },
       "(no readable suite_run.json beside " + Dir("damaged") + "/runs/tiny-seed2/report.json)"},
      {[](nlohmann::json*, const std::string& dir) { fs::remove(dir + "/report.json"); },
       "(no report.json in " + Dir("damaged") +
           "/runs/tiny-seed2); its suite.json says it finished: run the shard again"},
  };
  for (const Damage& damage : damages) {
    const std::string copy = Dir("damaged");
    fs::remove_all(copy);
    fs::copy(Dir(ShardDir(1, 2)), copy, fs::copy_options::recursive);
    nlohmann::json marker = nlohmann::json::parse(ReadFileBytes(copy + "/suite.json"));
    damage.apply(&marker, copy + "/runs/tiny-seed2");
    WriteFileAtomic(copy + "/suite.json", marker.dump(2));
    const std::string message = InputErrorOf([&] { MergeSuite({Dir(ShardDir(0, 2)), copy}); });
    EXPECT_NE(message.find(copy), std::string::npos) << message;
    EXPECT_NE(message.find(damage.expected), std::string::npos) << "expected '" << damage.expected << "' in:\n"
                                                                << message;
  }
}

TEST_F(SuiteShards, ARunReportWithoutAMethodAndAReportPathThatIsAFileAreNamed) {
  const std::string run = Dir("whole") + "/runs/tiny-seed1/report.json";
  const std::string message = InputErrorOf([&] { ReadSuiteRunResult("tiny-seed1", run, {"slcd", "nope"}); });
  EXPECT_NE(message.find(run + ": has no results of method nope"), std::string::npos) << message;
  const std::string file = InputErrorOf([&] { CheckSuiteReportFolder(Dir("suite.json")); });
  EXPECT_NE(file.find(Dir("suite.json") + ": is a file: expected a folder"), std::string::npos) << file;
}

TEST_F(SuiteShards, TheReportNeverOverwritesTheUsersFilesButGoesBesideTheShards) {
  const std::string cluster = Dir("cluster");  // the cluster layout: shard folders and logs beside the report
  fs::create_directories(cluster + "/shard-0");
  WriteFileAtomic(cluster + "/logs/merge.out", "log");
  EXPECT_NO_THROW(WriteSuiteReport(MergeSuite(Shards(2)), cluster));
  EXPECT_NO_THROW(WriteSuiteReport(MergeSuite(Shards(2)), cluster));  // an earlier report is its own
  const std::string users = Dir("users");
  WriteFileAtomic(users + "/suite_report.md", "my notes");
  const std::string message = InputErrorOf([&] { WriteSuiteReport(MergeSuite(Shards(2)), users); });
  EXPECT_NE(message.find(users + ": holds suite_report.md"), std::string::npos) << message;
  EXPECT_EQ(ReadFileBytes(users + "/suite_report.md"), "my notes");
  EXPECT_FALSE(fs::exists(users + "/suite_report.json"));
}

}  // namespace
}  // namespace hoilcd
