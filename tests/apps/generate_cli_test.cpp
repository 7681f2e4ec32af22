// hoilcd generate on the command line: scene files that validate, the same bytes at any thread
// count, and every error a user can trigger (bad layout, count 0 or huge, bad -o, bad --set).
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hoilcd/core/util/file_io.h"
#include "run_cli.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

// name -> bytes of every file in dir.
std::map<std::string, std::string> Files(const std::string& dir) {
  std::map<std::string, std::string> files;
  for (const fs::directory_entry& e : fs::directory_iterator(dir))
    files[e.path().filename().string()] = ReadFileBytes(e.path().string());
  return files;
}

TEST(GenerateCli, WritesScenesThatValidateTheSameBytesAtAnyThreadCountAndRewritesItsOwnFolder) {
  const test::TestDir temp;
  const test::CliOutcome one = test::RunCli(
      {"generate", "--layout", "mixed", "--count", "4", "--seed", "9", "-o", temp / "a", "--threads", "1"});
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_NE(one.out.find("generated 4 scenes"), std::string::npos) << one.out;
  const test::CliOutcome two = test::RunCli(
      {"generate", "--layout", "mixed", "--count", "4", "--seed", "9", "-o", temp / "b", "--threads", "2"});
  ASSERT_EQ(two.exit_code, 0) << two.err;
  const auto files = Files(temp / "a");
  EXPECT_EQ(files.size(), 4u);
  EXPECT_EQ(files, Files(temp / "b"));
  for (const auto& [name, bytes] : files) {
    const test::CliOutcome valid = test::RunCli({"validate", temp / "a" + "/" + name});
    EXPECT_EQ(valid.exit_code, 0) << name << ": " << valid.err;
    EXPECT_EQ(valid.err, "") << name;
  }
  // Its own earlier output is no obstacle; --start regenerates one scene of the run.
  const test::CliOutcome again =
      test::RunCli({"generate", "--layout", "mixed", "--count", "1", "--start", "2", "--seed", "9", "-o", temp / "a"});
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(Files(temp / "a"), files);
}

TEST(GenerateCli, EveryErrorAUserCanTriggerIsRefusedWithWhatWasExpected) {
  const test::TestDir temp;
  std::ofstream(temp / "notes.txt") << "mine";
  fs::create_directories(temp / "busy");
  std::ofstream(temp / "busy" + "/photo.png") << "png";
  std::ofstream(temp / "busy" + "/scene.json") << "{\"name\": \"mine\"}";
  const std::vector<std::pair<std::vector<std::string>, std::vector<std::string>>> cases = {
      {{"generate", "--layout", "kitchen", "-o", temp / "x"}, {"--layout", "one of: meeting_row", "got 'kitchen'"}},
      {{"generate", "--count", "0", "-o", temp / "x"}, {"--count", "expected a number in [1, 10000], got '0'"}},
      {{"generate", "--count", "1000000", "-o", temp / "x"}, {"--count", "got '1000000'"}},
      {{"generate", "--count", "2", "-o", temp / "notes.txt"}, {"notes.txt", "is a file: expected a folder"}},
      {{"generate", "--count", "2", "-o", temp / "busy"},
       {"busy", "photo.png", "scene.json", "not scenes hoilcd generate wrote"}},
      {{"generate", "--set", "occupancy_min=2", "-o", temp / "x"}, {"occupancy_min", "[0, 1]"}},
      {{"generate", "--set", "occupancy_max=0.1", "-o", temp / "x"}, {"occupancy_max", "at least occupancy_min"}},
      {{"generate", "--set", "no_such_option=1", "-o", temp / "x"}, {"no_such_option"}},
      {{"generate", "--count", "2"}, {"--output"}},
      {{"generate", "--start", "9999", "--count", "5", "-o", temp / "x"},
       {"--start 9999 --count 5", "indices up to 10000"}},
  };
  for (const auto& [args, expected] : cases) {
    const test::CliOutcome o = test::RunCli(args);
    EXPECT_NE(o.exit_code, 0) << args[2];
    for (const std::string& text : expected)
      EXPECT_NE(o.err.find(text), std::string::npos) << "expected '" << text << "' in: " << o.err;
  }
  EXPECT_FALSE(fs::exists(temp / "x")) << "a refused command writes nothing";
}

}  // namespace
}  // namespace hoilcd
