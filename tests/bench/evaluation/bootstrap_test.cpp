#include "hoilcd/bench/evaluation/bootstrap.h"

#include <cmath>

#include <gtest/gtest.h>

#include "hoilcd/core/util/random.h"

namespace hoilcd {
namespace {

// A scored query whose first true match is at rank 1 (hit) or 4 (miss), as a method's record.
QueryRecord Record(int frame, bool hit) {
  QueryRecord r;
  r.frame = frame;
  r.scored = true;
  r.reciprocal_rank = hit ? 1.0 : 0.25;
  r.recall_at_1 = hit ? 1 : 0;
  r.recall_at_5 = r.recall_at_10 = 1;
  r.top1_score = hit ? 2.0 : 1.0;
  r.top1_expected_correct = hit ? 1 : 0;
  r.top1_frame = 0;
  return r;
}

// Queries in runs of `run` identical outcomes, each run a hit with probability p.
std::vector<QueryRecord> Runs(int n, int run, double p, uint64_t seed) {
  Rng rng = KeyedRng(seed, "test.bootstrap");
  std::vector<QueryRecord> out;
  bool hit = false;
  for (int i = 0; i < n; ++i) {
    if (i % run == 0) hit = rng.Uniform() < p;
    out.push_back(Record(i, hit));
  }
  return out;
}

// The fraction of `trials` experiments whose MRR interval holds the true MRR.
double Coverage(int trials, int n, int run, int block, double p) {
  const double true_mrr = p * 1.0 + (1 - p) * 0.25;
  BootstrapPlan plan;
  plan.block_queries = block;
  plan.resamples = 400;
  plan.confidence = 0.95;
  int covered = 0;
  for (int t = 0; t < trials; ++t) {
    covered += BootstrapHeadline(Runs(n, run, p, 100 + t), plan, t, 1).mrr.Contains(true_mrr);
  }
  return static_cast<double>(covered) / trials;
}

TEST(Bootstrap, NinetyFivePercentIntervalsHoldTheTrueMrrInAboutNinetyFivePercentOfExperiments) {
  // Independent queries, blocks of one: the percentile interval's coverage is close to nominal
  // (small-sample percentile intervals run a little short of 95 %).
  const double coverage = Coverage(200, 300, 1, 1, 0.3);
  EXPECT_GE(coverage, 0.90);
  EXPECT_LE(coverage, 0.99);
}

TEST(Bootstrap, CorrelatedQueriesNeedBlocksTheLengthOfTheirCorrelation) {
  // Runs of 16 alike queries: resampling single queries claims far too much certainty; blocks of
  // 16 give back nearly the nominal coverage (100 runs: as many independent views as queries above).
  const double single = Coverage(120, 1600, 16, 1, 0.3);
  const double blocked = Coverage(120, 1600, 16, 16, 0.3);
  EXPECT_LT(single, 0.75) << single;
  EXPECT_GE(blocked, 0.85) << blocked;
}

TEST(Bootstrap, EveryHeadlineMetricGetsAnIntervalAroundItsValueTheSameAtAnyThreadCount) {
  const std::vector<QueryRecord> records = Runs(500, 5, 0.4, 7);
  const MethodMetrics m = SummariseQueries(records);
  BootstrapPlan plan;
  plan.block_queries = 5;
  plan.resamples = 300;
  plan.confidence = 0.95;
  const HeadlineIntervals one = BootstrapHeadline(records, plan, 3, 1);
  const HeadlineIntervals two = BootstrapHeadline(records, plan, 3, 2);
  EXPECT_EQ(one.ToJson().dump(), two.ToJson().dump());
  EXPECT_NE(BootstrapHeadline(records, plan, 4, 1).ToJson().dump(), one.ToJson().dump());  // seeded
  const std::pair<Interval, double> figures[] = {{one.mrr, m.mrr},
                                                 {one.recall_at_1, m.recall_at_1},
                                                 {one.recall_at_5, m.recall_at_5},
                                                 {one.pr_auc, m.pr_auc},
                                                 {one.recall_at_100p, m.recall_at_100p}};
  for (const auto& [interval, value] : figures) {
    EXPECT_LE(interval.low, value);
    EXPECT_GE(interval.high, value);
  }
  EXPECT_LT(one.mrr.low, one.mrr.high);
  EXPECT_EQ(one.recall_at_5.low, 1.0);  // every query within the top 5: no spread
  EXPECT_EQ(one.recall_at_5.high, 1.0);
}

std::vector<double> ReciprocalRanks(const std::vector<QueryRecord>& records) {
  std::vector<double> out;
  for (const QueryRecord& r : records) out.push_back(r.reciprocal_rank);
  return out;
}

TEST(Bootstrap, BlocksAreAsLongAsTheQueriesStayCorrelated) {
  // Independent queries: blocks of about one; runs of 16 alike queries: blocks of about that run.
  const double independent = OptimalBlockLength(ReciprocalRanks(Runs(2000, 1, 0.3, 5)));
  const double runs = OptimalBlockLength(ReciprocalRanks(Runs(2000, 16, 0.3, 5)));
  EXPECT_LT(independent, 3) << independent;
  EXPECT_GT(runs, 8) << runs;
  EXPECT_LT(runs, 60) << runs;
  EXPECT_EQ(OptimalBlockLength(std::vector<double>(100, 0.5)), 1);  // constant
  EXPECT_EQ(OptimalBlockLength({}), 1);
  EXPECT_LE(OptimalBlockLength(ReciprocalRanks(Runs(90, 45, 0.5, 5))), 30);  // at most n / 3
}

TEST(Bootstrap, OnePlanServesEveryMethodWithTheLongestBlockInQueriesAndSeconds) {
  BootstrapOptions options;
  std::vector<QueryRecord> alike = Runs(1000, 16, 0.3, 9), independent = Runs(1000, 1, 0.3, 9);
  const BootstrapPlan one = PlanBootstrap({&independent}, 10, options);
  const BootstrapPlan both = PlanBootstrap({&independent, &alike}, 10, options);
  EXPECT_EQ(both.block_queries, static_cast<int>(std::ceil(OptimalBlockLength(ReciprocalRanks(alike)))));
  EXPECT_LT(one.block_queries, both.block_queries);
  EXPECT_NEAR(both.block_s, both.block_queries / 10.0, 1e-9);  // a query per frame at 10 Hz
  for (QueryRecord& r : alike) r.frame *= 2;                   // a query every other frame: twice the time
  EXPECT_NEAR(PlanBootstrap({&alike}, 10, options).block_s, both.block_queries / 5.0, 0.3);
  EXPECT_EQ(both.resamples, options.resamples);
  BootstrapOptions bad;
  bad.confidence = 1;
  EXPECT_NE(bad.Check(), "");
}

TEST(Bootstrap, APairedComparisonNamesTheBetterMethodAndTheIntervalOfTheDifference) {
  std::vector<QueryRecord> a = Runs(200, 4, 0.5, 11), b = a;
  for (QueryRecord& r : b) r.reciprocal_rank -= 0.1;  // b exactly 0.1 worse on every query
  BootstrapPlan plan;
  plan.block_queries = 4;
  plan.resamples = 200;
  plan.confidence = 0.95;
  const PairedComparison ab = PairedBootstrap("dlcd", b, "slcd", a, plan, 1, 1);
  EXPECT_EQ(ab.a, "slcd");
  EXPECT_EQ(ab.b, "dlcd");
  EXPECT_NEAR(ab.delta, 0.1, 1e-12);
  EXPECT_NEAR(ab.interval.low, 0.1, 1e-12);
  EXPECT_NEAR(ab.interval.high, 0.1, 1e-12);
  EXPECT_TRUE(ab.Separated());
  EXPECT_EQ(ab.queries, 200);
  EXPECT_EQ(ab.ToString(), "slcd > dlcd: \xce\x94 0.100 [0.100, 0.100]");
  // Two methods that differ only by noise: an interval across 0.
  std::vector<QueryRecord> c = Runs(200, 4, 0.5, 12);
  const PairedComparison ac = PairedBootstrap("a", a, "c", c, plan, 1, 1);
  EXPECT_LE(ac.interval.low, ac.delta);
  EXPECT_GE(ac.interval.high, ac.delta);
  // A query one method could not score is left out of the pair.
  c[0].scored = false;
  EXPECT_EQ(PairedBootstrap("a", a, "c", c, plan, 1, 1).queries, 199);
}

}  // namespace
}  // namespace hoilcd
