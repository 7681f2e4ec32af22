// Suite files: a valid file read with paths resolved against its folder, runs sorted by name and
// chosen by split and shard, the identity a merge compares, and every problem a user can write
// reported with the file and JSON pointer.
#include "hoilcd/bench/pipeline/suite.h"

#include <chrono>
#include <filesystem>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "cpu_seconds.h"
#include "hoilcd/core/util/file_io.h"
#include "hoilcd/core/util/sizes.h"
#include "hoilcd/sim/generate/generator.h"
#include "input_error_of.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

const char* kGood = R"({
  "name": "s",
  "description": "two sequences",
  "sequences": [
    {"name": "room", "scene": "scenes/room.json", "seeds": [2, 1], "set": ["crowd.walkers=0"], "split": "dev"},
    {"name": "gen", "generate": {"layout": "lounge", "seed": 3, "index": 4}, "seeds": [5], "split": "test"}
  ]
})";

TEST(Suite, ReadsSequencesResolvesScenePathsAndSortsRunsByName) {
  const Suite suite = ParseSuite(kGood, "/data/suites/s.json");
  EXPECT_EQ(suite.name, "s");
  EXPECT_EQ(suite.description, "two sequences");
  ASSERT_EQ(suite.sequences.size(), 2u);
  EXPECT_EQ(suite.sequences[0].scene_path, "/data/suites/scenes/room.json");
  EXPECT_EQ(suite.sequences[0].sets, (std::vector<std::string>{"crowd.walkers=0"}));
  EXPECT_TRUE(suite.sequences[1].generated);
  EXPECT_EQ(suite.sequences[1].layout, "lounge");
  EXPECT_EQ(suite.sequences[1].generator_seed, 3u);
  EXPECT_EQ(suite.sequences[1].generator_index, 4);
  std::vector<std::string> names;
  for (const SuiteRunSpec& run : SuiteRuns(suite, "all")) names.push_back(run.name);
  EXPECT_EQ(names, (std::vector<std::string>{"gen-seed5", "room-seed1", "room-seed2"}));
  EXPECT_EQ(SuiteRuns(suite, "dev").size(), 2u);
  ASSERT_EQ(SuiteRuns(suite, "test").size(), 1u);
  EXPECT_EQ(SuiteRuns(suite, "test")[0].seed, 5);
}

struct BadSuite {
  std::string text;
  std::string expected;  // part of the message, with the JSON pointer
};

class SuiteErrors : public testing::TestWithParam<BadSuite> {};

TEST_P(SuiteErrors, NameTheFilePointerAndWhatWasExpected) {
  const std::string message = test::InputErrorOf([&] { ParseSuite(GetParam().text, "my_suite.json"); });
  EXPECT_NE(message.find("my_suite.json"), std::string::npos) << message;
  EXPECT_NE(message.find(GetParam().expected), std::string::npos) << "expected '" << GetParam().expected << "' in:\n"
                                                                  << message;
}

std::string One(const std::string& sequence) { return R"({"name": "s", "sequences": [)" + sequence + "]}"; }

INSTANTIATE_TEST_SUITE_P(
    Suite, SuiteErrors,
    testing::Values(
        BadSuite{"{", "invalid JSON"}, BadSuite{"[]", "/: expected an object"},
        BadSuite{R"({"sequences": []})", "/name: missing"}, BadSuite{R"({"name": "s"})", "/sequences: missing"},
        BadSuite{R"({"name": "s", "sequences": []})", "/sequences: expected at least one sequence"},
        BadSuite{R"({"name": "s", "sequences": {}})", "/sequences: expected an array"},
        BadSuite{R"({"name": "s", "sequences": [{}], "typo": 1})", "/typo: unknown key"},
        BadSuite{One("3"), "/sequences/0: expected an object"},
        BadSuite{One(R"({"name": "a", "scene": "x.json", "seeds": [1], "split": "dev", "seed": 2})"),
                 "/sequences/0/seed: unknown key"},
        BadSuite{One(R"({"scene": "x.json", "seeds": [1], "split": "dev"})"), "/sequences/0/name: missing"},
        BadSuite{One(R"({"name": "a b", "scene": "x.json", "seeds": [1], "split": "dev"})"),
                 "/sequences/0/name: expected 1-100 letters"},
        BadSuite{One(R"({"name": "a", "seeds": [1], "split": "dev"})"),
                 "/sequences/0: expected exactly one of \"scene\""},
        BadSuite{One(R"({"name": "a", "scene": "x.json", "generate": {}, "seeds": [1], "split": "dev"})"),
                 "expected exactly one of"},
        BadSuite{One(R"({"name": "a", "scene": 3, "seeds": [1], "split": "dev"})"),
                 "/sequences/0/scene: expected a string"},
        BadSuite{One(R"({"name": "a", "scene": "", "seeds": [1], "split": "dev"})"),
                 "/sequences/0/scene: expected a scene file path"},
        BadSuite{One(R"({"name": "a", "generate": [], "seeds": [1], "split": "dev"})"),
                 "/sequences/0/generate: expected an object"},
        BadSuite{
            One(R"({"name": "a", "generate": {"layout": "lounge", "seed": 1, "index": 0, "count": 2}, "seeds": [1], "split": "dev"})"),
            "/sequences/0/generate/count: unknown key"},
        BadSuite{
            One(R"({"name": "a", "generate": {"layout": "castle", "seed": 1, "index": 0}, "seeds": [1], "split": "dev"})"),
            "/sequences/0/generate/layout: expected a layout family"},
        BadSuite{One(R"({"name": "a", "generate": {"layout": "lounge", "index": 0}, "seeds": [1], "split": "dev"})"),
                 "/sequences/0/generate/seed: missing"},
        BadSuite{
            One(R"({"name": "a", "generate": {"layout": "lounge", "seed": -1, "index": 0}, "seeds": [1], "split": "dev"})"),
            "/sequences/0/generate/seed: expected a non-negative integer"},
        BadSuite{
            One(R"({"name": "a", "generate": {"layout": "lounge", "seed": 1, "index": -2}, "seeds": [1], "split": "dev"})"),
            "/sequences/0/generate/index: expected a scene index in [0, 10000], got -2"},
        BadSuite{
            One(R"({"name": "a", "generate": {"layout": "lounge", "seed": 1, "index": 10001}, "seeds": [1], "split": "dev"})"),
            "/sequences/0/generate/index: expected a scene index in [0, 10000], got 10001"},
        BadSuite{
            One(R"({"name": "a", "generate": {"layout": "lounge", "seed": 9007199254740993, "index": 0}, "seeds": [1], "split": "dev"})"),
            "/sequences/0/generate/seed: expected a seed in [0, 9007199254740992], got 9007199254740993"},
        BadSuite{One(R"({"name": "a", "scene": "x.json", "seeds": [1], "seeds": [2], "split": "dev"})"),
                 "/sequences/0/seeds: the key \"seeds\" is repeated in one object"},
        BadSuite{R"({"name": "s", "name": "t", "sequences": []})",
                 "my_suite.json: /name: the key \"name\" is repeated"},
        BadSuite{One(R"({"name": "a", "scene": "x.json", "split": "dev"})"), "/sequences/0/seeds: missing"},
        BadSuite{One(R"({"name": "a", "scene": "x.json", "seeds": 1, "split": "dev"})"),
                 "/sequences/0/seeds: expected an array"},
        BadSuite{One(R"({"name": "a", "scene": "x.json", "seeds": [], "split": "dev"})"),
                 "/sequences/0/seeds: expected at least one seed"},
        BadSuite{One(R"({"name": "a", "scene": "x.json", "seeds": [1.5], "split": "dev"})"),
                 "/sequences/0/seeds/0: expected a 32-bit integer"},
        BadSuite{One(R"({"name": "a", "scene": "x.json", "seeds": [-1], "split": "dev"})"),
                 "/sequences/0/seeds/0: expected a non-negative seed"},
        BadSuite{One(R"({"name": "a", "scene": "x.json", "seeds": [1, 1], "split": "dev"})"),
                 "/sequences/0/seeds/1: seed 1 is listed twice"},
        BadSuite{One(R"({"name": "a", "scene": "x.json", "seeds": [1], "set": "frames=3", "split": "dev"})"),
                 "/sequences/0/set: expected an array"},
        BadSuite{One(R"({"name": "a", "scene": "x.json", "seeds": [1], "set": [3], "split": "dev"})"),
                 "/sequences/0/set/0: expected a string"},
        BadSuite{One(R"({"name": "a", "scene": "x.json", "seeds": [1], "set": ["frames"], "split": "dev"})"),
                 "/sequences/0/set/0: expected \"key=value\""},
        BadSuite{One(R"({"name": "a", "scene": "x.json", "seeds": [1], "set": ["seed=4"], "split": "dev"})"),
                 "/sequences/0/set/0: the seed is given by \"seeds\""},
        BadSuite{One(R"({"name": "a", "scene": "x.json", "seeds": [1]})"), "/sequences/0/split: missing"},
        BadSuite{One(R"({"name": "a", "scene": "x.json", "seeds": [1], "split": "train"})"),
                 "/sequences/0/split: expected \"dev\" or \"test\""},
        BadSuite{R"({"name": "s", "sequences": [{"name": "a", "scene": "x.json", "seeds": [1], "split": "dev"},
                                                  {"name": "a", "scene": "y.json", "seeds": [1], "split": "dev"}]})",
                 "/sequences/1/name: sequence name \"a\" is used twice"}));

TEST(Suite, AGeneratedSceneIndexAndSeedAtTheirBoundsAreRead) {
  const Suite suite = ParseSuite(
      One(R"({"name": "a", "generate": {"layout": "lounge", "seed": 9007199254740992, "index": 10000}, "seeds": [1], "split": "dev"})"),
      "s.json");
  EXPECT_EQ(suite.sequences[0].generator_seed, kMaxSeed);
  EXPECT_EQ(suite.sequences[0].generator_index, kMaxGeneratedSceneIndex);
}

TEST(Suite, NestingAHundredThousandDeepOrAHundredThousandItemsIsRefusedWithinTwoSeconds) {
  const auto seconds_and_error = [](const std::string& text) {
    const double start = test::ProcessCpuSeconds();  // CPU time: a loaded machine stretches wall time
    const std::string error = test::InputErrorOf([&] { ParseSuite(text, "my_suite.json"); });
    return std::make_pair(test::ProcessCpuSeconds() - start, error);
  };
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  std::string many_seeds, many_sets, many_sequences;
  for (int i = 0; i < 100000; ++i) {
    many_seeds += (i ? "," : "") + std::to_string(i);
    many_sets += std::string(i ? "," : "") + "\"crowd.walkers=" + std::to_string(i) + "\"";
    many_sequences += std::string(i ? "," : "") + R"({"name": "a)" + std::to_string(i) +
                      R"(", "scene": "x.json", "seeds": [1], "split": "dev"})";
  }
  const std::pair<std::string, std::string> cases[] = {
      {R"({"name": "s", "description": )" + deep + "}", "my_suite.json: /description/0/0/"},
      {One(R"({"name": "a", "scene": "x.json", "seeds": [1], "set": )" + deep + R"(, "split": "dev"})"),
       "my_suite.json: /sequences/0/set/0/"},
      {One(R"({"name": "a", "scene": "x.json", "seeds": [)" + many_seeds + R"(], "split": "dev"})"),
       "my_suite.json: /sequences/0/seeds: holds 100000 items; expected at most 10000"},
      {One(R"({"name": "a", "scene": "x.json", "seeds": [1], "set": [)" + many_sets + R"(], "split": "dev"})"),
       "my_suite.json: /sequences/0/set: holds 100000 items; expected at most 256"},
      {R"({"name": "s", "sequences": [)" + many_sequences + "]}",
       "my_suite.json: /sequences: holds 100000 items; expected at most 10000"}};
  for (const auto& [text, expected] : cases) {
    const auto [seconds, error] = seconds_and_error(text);
    EXPECT_LT(seconds, 2.0) << expected;
    EXPECT_NE(error.find(expected), std::string::npos) << error.substr(0, 300);
  }
}

TEST(Suite, ShippedSuitesReadAndNameSceneFilesThatExist) {
  for (const char* name : {"ci", "standard"}) {
    const Suite suite = ReadSuite(std::string(HOILCD_TEST_SOURCE_DIR) + "/suites/" + name + ".json");
    EXPECT_EQ(suite.name, name);
    EXPECT_FALSE(SuiteRuns(suite, "dev").empty()) << name;
    EXPECT_FALSE(SuiteRuns(suite, "test").empty()) << name;
    for (const SuiteSequence& s : suite.sequences) {
      if (!s.generated) {
        EXPECT_TRUE(std::filesystem::exists(s.scene_path)) << name << ": " << s.scene_path;
      }
    }
  }
  EXPECT_GE(ReadSuite(std::string(HOILCD_TEST_SOURCE_DIR) + "/suites/standard.json").sequences.size(), 12u);
}

TEST(Suite, AMissingFileIsNamed) {
  const std::string message = test::InputErrorOf([] { ReadSuite("/nonexistent/suite.json"); });
  EXPECT_NE(message.find("/nonexistent/suite.json"), std::string::npos) << message;
  EXPECT_NE(message.find("cannot read the suite file"), std::string::npos) << message;
}

TEST(Suite, OptionsRefuseAnUnknownSplitAMissingFolderAndABadShard) {
  SuiteOptions options;
  EXPECT_NE(options.Check().find("output_dir"), std::string::npos) << options.Check();
  options.output_dir = "out";
  EXPECT_EQ(options.Check(), "");
  options.shard = {2, 2};
  EXPECT_EQ(options.Check(), "shard: the shard index must be in 0..1");
  options.shard = {};
  options.split = "train";
  EXPECT_NE(options.Check().find("split"), std::string::npos) << options.Check();
}

TEST(Suite, ShardsOfOneToFiveCoverEveryRunOfTheSplitExactlyOnce) {
  const Suite suite = ParseSuite(R"({"name": "s", "sequences": [
    {"name": "a", "scene": "a.json", "seeds": [4, 1, 3, 2], "split": "dev"},
    {"name": "b", "generate": {"layout": "lounge", "seed": 1, "index": 0}, "seeds": [9, 7, 8], "split": "test"}]})",
                                 "s.json");
  for (const char* split : {"all", "dev", "test"}) {
    const std::vector<SuiteRunSpec> runs = SuiteRuns(suite, split);
    std::multiset<std::string> expected;
    for (const SuiteRunSpec& run : runs) expected.insert(run.name);
    for (int count = 1; count <= 5; ++count) {
      std::multiset<std::string> from_shards;
      for (int index = 0; index < count; ++index) {
        for (const SuiteRunSpec& run : ShardOf(runs, Shard{index, count})) from_shards.insert(run.name);
      }
      EXPECT_EQ(from_shards, expected) << split << " in " << count << " shards";
    }
  }
  EXPECT_EQ(SuiteRuns(suite, "all").size(), 7u);
}

TEST(Suite, IdentityKnowsASceneByItsBytesNotItsPathAndHoldsOnlyTheSplitsSequences) {
  const test::TestDir here("here"), there("there");
  const std::string scene = R"({"name": "room", "frames": 10})";
  WriteFileAtomic(here / "scenes/room.json", scene);
  WriteFileAtomic(there / "elsewhere/room.json", scene);
  const auto suite_text = [](const std::string& scene_path) {
    return R"({"name": "s", "sequences": [
      {"name": "room", "scene": ")" +
           scene_path + R"(", "seeds": [1, 2], "split": "dev"},
      {"name": "gen", "generate": {"layout": "lounge", "seed": 3, "index": 0}, "seeds": [5], "set": ["frames=9"], "split": "test"}]})";
  };
  const nlohmann::json bench = {{"methods", {"slcd"}}};
  const Suite a = ParseSuite(suite_text("scenes/room.json"), here / "suite.json");
  const Suite b = ParseSuite(suite_text("elsewhere/room.json"), there / "suite.json");
  EXPECT_EQ(SuiteIdentity(a, "all", bench), SuiteIdentity(b, "all", bench));

  const nlohmann::json identity = SuiteIdentity(a, "all", bench);
  EXPECT_EQ(identity["sequences"][0]["scene_checksum"], ChecksumOf(scene));
  // A generated sequence by its spec and the generator's version (another version, another scene).
  EXPECT_EQ(
      identity["sequences"][1]["generate"],
      (nlohmann::json{{"layout", "lounge"}, {"seed", 3}, {"index", 0}, {"generator_version", kGeneratorVersion}}));
  EXPECT_EQ(identity["runs"], (nlohmann::json{"gen-seed5", "room-seed1", "room-seed2"}));
  EXPECT_EQ(identity["bench"], bench);
  const nlohmann::json dev = SuiteIdentity(a, "dev", bench);
  EXPECT_EQ(dev["split"], "dev");
  ASSERT_EQ(dev["sequences"].size(), 1u);
  EXPECT_EQ(dev["runs"], (nlohmann::json{"room-seed1", "room-seed2"}));

  WriteFileAtomic(there / "elsewhere/room.json", R"({"name": "room", "frames": 11})");
  EXPECT_NE(SuiteIdentity(b, "all", bench)["sequences"][0]["scene_checksum"],
            identity["sequences"][0]["scene_checksum"]);
  std::filesystem::remove(there / "elsewhere/room.json");
  EXPECT_TRUE(SuiteIdentity(b, "all", bench)["sequences"][0]["scene_checksum"].is_null());
}

}  // namespace
}  // namespace hoilcd
