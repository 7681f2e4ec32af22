// Number flags: every one refuses NaN, infinities, text and values out of its range before any
// work, naming the flag and the range in a few words (issue 32: --max-drop nan turned the CI gate
// off; --max-drop -0.1 printed the bounds of a double in 309 digits).
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "run_cli.h"
#include "shared.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

TEST(NumberIn, AcceptsFiniteNumbersInRangeOnly) {
  CLI::Validator v = NumberIn(OptionRange().AtLeast(0));
  for (std::string ok : {"0", "0.5", "12", "1e3"}) EXPECT_EQ(v(ok), "") << ok;
  for (std::string bad : {"nan", "NaN", "inf", "-inf", "-0.1", "abc", "1x", ""}) EXPECT_NE(v(bad), "") << bad;
  std::string text = "-0.1";
  EXPECT_EQ(v(text), "expected a number at least 0, got '-0.1'");
}

TEST(Flags, EveryNumberFlagRefusesNanAndOutOfRangeValuesNamingTheFlagBriefly) {
  const test::TestDir temp;
  const std::string scene = std::string(HOILCD_TEST_SOURCE_DIR) + "/tests/data/tiny_room.json";
  const std::string report = temp / "report.json";
  const std::vector<std::vector<std::string>> cases = {
      {"bench", temp.str(), "--baseline", report, "--max-drop", "nan"},
      {"bench", temp.str(), "--baseline", report, "--max-drop", "-0.1"},
      {"bench", temp.str(), "--baseline", report, "--max-drop", "2"},
      {"bench", temp.str(), "--baseline", report, "--max-drop", "cis"},
      {"bench", temp.str(), "--overlap-threshold", "0"},
      {"bench", temp.str(), "--overlap-stride", "0"},
      {"bench", temp.str(), "--overlap-depth-tolerance", "nan"},
      {"bench", temp.str(), "--radius", "nan"},
      {"bench", temp.str(), "--exclusion-window", "inf"},
      {"bench", temp.str(), "--heading-tolerance", "nan"},
      {"bench", temp.str(), "--loop-threshold", "nan"},
      {"bench", temp.str(), "--threads", "-1"},
      {"bench", temp.str(), "--online", "--shortlist-k", "-1"},
      {"bench", temp.str(), "--online", "--shortlist-search-depth", "nan"},
      {"render", scene, "-o", temp / "out", "--frames", "-3"},
      {"render", scene, "-o", temp / "out", "--seed", "-1"},
      {"sweep", scene, "-o", temp / "sweep", "--seeds", "0"},
      {"sweep", scene, "-o", temp / "sweep", "--seeds", "2147483647"},
      {"suite", scene, "-o", temp / "suite", "--threads", "-1"},
      {"suite", scene, "-o", temp / "suite", "--radius", "nan"},
  };
  for (const std::vector<std::string>& args : cases) {
    const test::CliOutcome o = test::RunCli(args);
    const std::string flag = args[args.size() - 2];
    EXPECT_NE(o.exit_code, 0) << flag << " " << args.back();
    EXPECT_NE(o.err.find(flag), std::string::npos) << o.err;
    EXPECT_NE(o.err.find("expected a"), std::string::npos) << o.err;
    EXPECT_LT(o.err.size(), 300u) << o.err;
    EXPECT_EQ(o.err.find("1797693"), std::string::npos) << o.err;
  }
}

TEST(Flags, ShortlistFlagsNeedOnlineAndTheIndexIsOneOfFaisssTwo) {
  const test::TestDir temp;
  const test::CliOutcome without = test::RunCli({"bench", temp.str(), "--shortlist-k", "5"});
  EXPECT_NE(without.exit_code, 0);
  EXPECT_NE(without.err.find("--online"), std::string::npos) << without.err;
  const test::CliOutcome index = test::RunCli({"bench", temp.str(), "--online", "--shortlist-index", "ivf"});
  EXPECT_NE(index.exit_code, 0);
  EXPECT_NE(index.err.find("--shortlist-index"), std::string::npos) << index.err;
}

}  // namespace
}  // namespace hoilcd
