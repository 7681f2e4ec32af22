// Every number flag of every command at the edges of its range, given as text that a double would
// round (issue 45): a bound itself is taken when it is inclusive and refused when exclusive, and
// the first value beyond it is refused, 2^53 + 1 included, which a double holds as 2^53.
#include <cstdio>
#include <regex>
#include <string>
#include <tuple>
#include <vector>

#include <CLI/CLI.hpp>
#include <gtest/gtest.h>

#include "command.h"
#include "hoilcd/core/util/sizes.h"
#include "run_cli.h"
#include "shared.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

TEST(NumberIn, ComparesWholeNumbersAsWholeNumbers) {
  CLI::Validator v = NumberIn(OptionRange::Closed(0, static_cast<double>(kMaxSeed)));
  for (std::string ok : {"0", "9007199254740992", "+5", "9007199254740991", "1e3", "0.5"}) EXPECT_EQ(v(ok), "") << ok;
  for (std::string bad : {"9007199254740993", "9007199254740999", "18446744073709551615", "18446744073709551616",
                          "99999999999999999999999", "-1", "-9223372036854775809"}) {
    EXPECT_NE(v(bad), "") << bad;
  }
  CLI::Validator at_least = NumberIn(OptionRange().AtLeast(0));
  std::string huge = "99999999999999999999999";  // beyond 64 bits, but no bound above
  EXPECT_EQ(at_least(huge), "");
}

// The text of the first value past `bound` on its side: one more whole number for a whole bound,
// else the bound with a tail of digits a double rounds away (or 1e-400 past 0), which must be
// refused like the bound itself when the bound is exclusive.
std::string Beyond(const std::string& bound, bool above, bool exclusive) {
  if (exclusive) {
    if (bound == "0") return above ? "-1e-400" : "1e-400";
    return bound + (bound.find('.') == std::string::npos ? ".000000000000000000001" : "000000000000000000001");
  }
  if (bound.find_first_not_of("-0123456789") != std::string::npos) return "";
  const long double value = std::stold(bound) + (above ? 1 : -1);
  char text[64];
  std::snprintf(text, sizeof text, "%.0Lf", value);
  return text;
}

TEST(NumberFlags, EveryBoundOfEveryCommandHoldsForTextADoubleWouldRound) {
  CLI::App app;
  for (auto add : {AddValidateCommand, AddRenderCommand, AddMergeCommand, AddBenchCommand, AddRunCommand,
                   AddEvaluateCommand, AddInspectCommand, AddSweepCommand, AddExportCocoCommand, AddParamsCommand,
                   AddExportMotCommand, AddReferenceCommand, AddGenerateCommand, AddSuiteCommand, AddRealismCommand}) {
    add(&app);
  }
  // NumberIn's description: "in [0, 10]", "in (0, 1]", "at least 0", "above 0", "at most 5", "below 5".
  const std::regex interval(R"(in ([\[(])(-?[0-9.e+]+), (-?[0-9.e+]+)([\])]).*)");
  const std::regex one_side(R"((at least|above|at most|below) (-?[0-9.e+]+).*)");
  int bounds = 0;
  for (CLI::App* command : app.get_subcommands([](CLI::App*) { return true; })) {
    for (CLI::Option* option : command->get_options()) {
      for (int i = 0;; ++i) {
        CLI::Validator* validator = nullptr;
        try {
          validator = option->get_validator(i);
        } catch (const CLI::OptionNotFound&) {
          break;
        }
        const std::string description = validator->get_description();
        std::vector<std::tuple<std::string, bool, bool>> edges;  // bound, upper, exclusive
        std::smatch m;
        if (std::regex_match(description, m, interval)) {
          edges = {{m[2], false, m[1] == "("}, {m[3], true, m[4] == ")"}};
        } else if (std::regex_match(description, m, one_side)) {
          const std::string side = m[1];
          edges = {{m[2], side == "at most" || side == "below", side == "above" || side == "below"}};
        }
        for (const auto& [bound, upper, exclusive] : edges) {
          const std::string where = command->get_name() + " " + option->get_name() + " (" + description + ")";
          std::string at = bound;
          EXPECT_EQ((*validator)(at).empty(), !exclusive) << where << ": " << bound;
          std::string beyond = Beyond(bound, upper, exclusive);
          if (beyond.empty()) continue;
          EXPECT_NE((*validator)(beyond), "") << where << ": " << beyond;
          ++bounds;
        }
      }
    }
  }
  EXPECT_GT(bounds, 20);
}

TEST(NumberFlags, SeedsAboveTwoToThe53AreRefusedByGenerateRenderAndValidate) {
  const test::TestDir temp;
  const std::string scene = std::string(HOILCD_TEST_SOURCE_DIR) + "/tests/data/tiny_room.json";
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"generate", "--layout", "lounge", "-o", temp / "g", "--seed", "9007199254740993"},
        std::vector<std::string>{"render", scene, "-o", temp / "r", "--seed", "9007199254740993"},
        std::vector<std::string>{"validate", scene, "--seed", "9007199254740993"}}) {
    const test::CliOutcome o = test::RunCli(args);
    EXPECT_NE(o.exit_code, 0) << args[0];
    EXPECT_NE(o.err.find("--seed"), std::string::npos) << o.err;
    EXPECT_NE(o.err.find("expected a number in [0, 9007199254740992], got '9007199254740993'"), std::string::npos)
        << args[0] << ": " << o.err;
  }
  const test::CliOutcome valid = test::RunCli({"validate", scene, "--seed", "9007199254740992"});
  EXPECT_EQ(valid.exit_code, 0) << valid.err;
}

TEST(Validate, AFolderIsNamedAsOne) {
  const test::TestDir temp;
  const test::CliOutcome o = test::RunCli({"validate", temp.str()});
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_NE(o.err.find(temp.str() + ": is a folder: expected a regular file"), std::string::npos) << o.err;
  EXPECT_EQ(o.err.find("JSON"), std::string::npos) << o.err;
}

}  // namespace
}  // namespace hoilcd
