// The suite summary on constructed numbers: a hand-checked mean, ranks with ties, paired wins,
// an interval that covers the mean and is the same bytes on a rerun, failed runs listed apart.
#include "hoilcd/bench/evaluation/suite_summary.h"

#include <cmath>

#include <gtest/gtest.h>

namespace hoilcd {
namespace {

SuiteRunResult Run(const std::string& name, double a, double b, double c) {
  return {name, "", {{"a", a}, {"b", b}, {"c", c}}, {{"a", a / 2}, {"b", b / 2}, {"c", c / 2}}, ""};
}

std::vector<SuiteRunResult> Runs() {
  return {Run("r1", 0.9, 0.5, 0.5),
          Run("r2", 0.6, 0.7, 0.1),
          Run("r3", 0.3, 0.3, 0.3),
          Run("r4", 0.8, 0.2, 0.4),
          {"r5", "scene missing", {}, {}, ""}};
}

TEST(SuiteSummary, RanksGiveTiedValuesTheirMeanRankAndNanTheLast) {
  EXPECT_EQ(RanksDescending({0.9, 0.5, 0.5}), (std::vector<double>{1, 2.5, 2.5}));
  EXPECT_EQ(RanksDescending({0.3, 0.3, 0.3}), (std::vector<double>{2, 2, 2}));
  EXPECT_EQ(RanksDescending({NAN, 0.1, 0.7}), (std::vector<double>{3, 2, 1}));
  EXPECT_EQ(RanksDescending({NAN, 0.1, NAN}), (std::vector<double>{2.5, 1, 2.5}));
}

TEST(SuiteSummary, MeansRanksAndWinsMatchAHandCount) {
  const SuiteSummary s = SummariseSuite("t", "", {"a", "b", "c"}, Runs());
  ASSERT_EQ(s.runs.size(), 4u);
  ASSERT_EQ(s.failed.size(), 1u);
  EXPECT_EQ(s.failed[0].first, "r5");
  EXPECT_EQ(s.failed[0].second, "scene missing");
  EXPECT_NEAR(s.methods[0].mean_mrr, (0.9 + 0.6 + 0.3 + 0.8) / 4, 1e-12);
  EXPECT_NEAR(s.methods[1].mean_recall_at_1, (0.5 + 0.7 + 0.3 + 0.2) / 8, 1e-12);
  // a: ranks 1, 2, 2, 1; b: 2.5, 1, 2, 3; c: 2.5, 3, 2, 2.
  EXPECT_EQ(s.methods[0].rank, (std::vector<double>{1, 2, 2, 1}));
  EXPECT_EQ(s.methods[1].rank, (std::vector<double>{2.5, 1, 2, 3}));
  EXPECT_DOUBLE_EQ(s.methods[0].mean_rank, 1.5);
  EXPECT_DOUBLE_EQ(s.methods[2].mean_rank, 2.375);
  ASSERT_EQ(s.wins.size(), 3u);  // a-b, a-c, b-c
  EXPECT_EQ(s.wins[0].a_wins, 2);
  EXPECT_EQ(s.wins[0].b_wins, 1);
  EXPECT_EQ(s.wins[0].ties, 1);
  EXPECT_EQ(s.wins[0].ToString(), "a beats b on 2 of 4 (1 tie)");
  EXPECT_EQ(s.wins[2].ToString(), "b and c each win 1 of 4 (2 ties)");
}

TEST(SuiteSummary, IntervalCoversTheMeanAndIsTheSameBytesOnARerun) {
  const SuiteSummary s = SummariseSuite("t", "d", {"a", "b", "c"}, Runs());
  for (const SuiteMethodSummary& m : s.methods) {
    EXPECT_TRUE(m.mrr_interval.Contains(m.mean_mrr)) << m.method;
    EXPECT_LT(m.mrr_interval.low, m.mrr_interval.high) << m.method;
    EXPECT_GE(m.mrr_interval.low, 0.1);
    EXPECT_LE(m.mrr_interval.high, 0.9);
  }
  const SuiteSummary again = SummariseSuite("t", "d", {"a", "b", "c"}, Runs());
  EXPECT_EQ(s.ToJson().dump(2), again.ToJson().dump(2));
  EXPECT_EQ(s.ToMarkdown(), again.ToMarkdown());
  EXPECT_NE(s.ToMarkdown().find("r5: scene missing"), std::string::npos);
}

TEST(SuiteSummary, SeedsOfOneSequenceAreAveragedBeforeTheSequencesAreComparedAndResampled) {
  // Room A on two seeds, room B on one: over runs a would lead (0.6 against 0.533); over rooms,
  // each the mean of its seeds, b does (0.55 against 0.5), and each wins one room.
  auto run = [](const std::string& name, const std::string& sequence, double a, double b) {
    return SuiteRunResult{name, "", {{"a", a}, {"b", b}}, {{"a", a}, {"b", b}}, sequence};
  };
  const SuiteSummary s = SummariseSuite("t", "", {"a", "b"},
                                        {run("A-seed1", "A", 0.9, 0.5),
                                         run("A-seed2", "A", 0.7, 0.5),
                                         run("B-seed1", "B", 0.2, 0.6),
                                         {"B-seed2", "render failed", {}, {}, "B"}});
  EXPECT_EQ(s.runs, (std::vector<std::string>{"A-seed1", "A-seed2", "B-seed1"}));
  EXPECT_EQ(s.sequences, (std::vector<std::string>{"A", "B"}));
  EXPECT_NEAR(s.methods[0].sequence_mrr[0], 0.8, 1e-12);
  EXPECT_NEAR(s.methods[0].mean_mrr, 0.5, 1e-12);
  EXPECT_NEAR(s.methods[1].mean_mrr, 0.55, 1e-12);
  EXPECT_EQ(s.methods[0].sequence_rank, (std::vector<double>{1, 2}));
  EXPECT_DOUBLE_EQ(s.methods[0].mean_rank, 1.5);
  EXPECT_EQ(s.methods[0].rank, (std::vector<double>{1, 1, 2}));  // per run, for the run table
  EXPECT_EQ(s.wins[0].ToString(), "a and b each win 1 of 2");
  // Resampling two rooms: every resample's mean is 0.2, 0.5 or 0.8.
  EXPECT_GE(s.methods[0].mrr_interval.low, 0.2 - 1e-12);
  EXPECT_LE(s.methods[0].mrr_interval.high, 0.8 + 1e-12);
  EXPECT_TRUE(s.methods[0].mrr_interval.Contains(0.5));
  const std::string md = s.ToMarkdown();
  EXPECT_NE(md.find("3 runs of 2 sequences finished, 1 failed"), std::string::npos) << md;
  EXPECT_NE(md.find("| A | 0.800 (1.0) | 0.500 (2.0) |"), std::string::npos) << md;
  EXPECT_EQ(s.ToJson()["methods"][1]["sequences"]["B"]["mrr"], 0.6);
}

TEST(SuiteSummary, OneValueGivesAPointIntervalAndNoValueNone) {
  const Interval one = BootstrapMeanInterval({0.4}, {}, "x");
  EXPECT_DOUBLE_EQ(one.low, 0.4);
  EXPECT_DOUBLE_EQ(one.high, 0.4);
  EXPECT_TRUE(std::isnan(BootstrapMeanInterval({}, {}, "x").low));
}

}  // namespace
}  // namespace hoilcd
