#include "hoilcd/bench/evaluation/metrics.h"

#include <algorithm>
#include <numeric>

#include <gtest/gtest.h>

#include "hoilcd/core/util/random.h"

namespace hoilcd {
namespace {

// Frames 0..n-1 on a line, 1 m apart.
std::vector<PoseRecord> LinePoses(int n) {
  std::vector<PoseRecord> poses(n);
  for (int i = 0; i < n; ++i) {
    poses[i].frame = i;
    poses[i].time_s = i;
    poses[i].x_m = i;
  }
  return poses;
}

Query MakeQuery(int frame, std::vector<int> database, std::vector<uint8_t> is_true, int lap = 1) {
  Query q;
  q.frame = frame;
  q.lap = lap;
  q.database = std::move(database);
  q.is_true_match = std::move(is_true);
  return q;
}

// Brute force: every order of the tied items (ties broken by a permutation, all equally likely).
void BruteForce(const std::vector<double>& scores, const std::vector<uint8_t>& is_true, double* expected_rr,
                std::vector<double>* recall_at) {
  std::vector<int> order(scores.size());
  std::iota(order.begin(), order.end(), 0);
  double sum_rr = 0;
  std::vector<double> hits(recall_at->size(), 0.0);
  int permutations = 0;
  do {
    // Rank = 1 + items before the first true match: higher score first, ties by `order`.
    std::vector<int> ranking(scores.size());
    std::iota(ranking.begin(), ranking.end(), 0);
    std::sort(ranking.begin(), ranking.end(),
              [&](int a, int b) { return scores[a] != scores[b] ? scores[a] > scores[b] : order[a] < order[b]; });
    int rank = 0;
    while (!is_true[ranking[rank]]) ++rank;
    sum_rr += 1.0 / (rank + 1);
    for (size_t k = 0; k < hits.size(); ++k) hits[k] += (rank + 1 <= static_cast<int>(k)) ? 1 : 0;
    ++permutations;
  } while (std::next_permutation(order.begin(), order.end()));
  *expected_rr = sum_rr / permutations;
  for (size_t k = 0; k < hits.size(); ++k) (*recall_at)[k] = hits[k] / permutations;
}

TEST(FirstTrueRank, OneTrueAmongThreeTiedAtTopHasTheHandComputedExpectation) {
  const FirstTrueRank rank = RankFirstTrueMatch({5, 5, 5, 1}, {0, 1, 0, 0});
  EXPECT_EQ(rank.above, 0);
  EXPECT_EQ(rank.tie_size, 3);
  EXPECT_EQ(rank.tie_true, 1);
  EXPECT_NEAR(rank.ExpectedReciprocalRank(), (1 + 1.0 / 2 + 1.0 / 3) / 3, 1e-15);
  EXPECT_NEAR(rank.ExpectedRank(), 2.0, 1e-15);
  EXPECT_NEAR(rank.RecallAtK(1), 1.0 / 3, 1e-15);
  EXPECT_NEAR(rank.RecallAtK(2), 2.0 / 3, 1e-15);
  EXPECT_EQ(rank.RecallAtK(3), 1.0);
}

TEST(FirstTrueRank, TwoTrueInATieBelowABetterFalseMatch) {
  // s = 1 above; g = 4 tied with t = 2 true: first true at 1, 2, 3 with P = 1/2, 1/3, 1/6.
  const FirstTrueRank rank = RankFirstTrueMatch({9, 5, 5, 5, 5, 0}, {0, 1, 0, 1, 0, 1});
  EXPECT_EQ(rank.above, 1);
  EXPECT_NEAR(rank.ExpectedReciprocalRank(), 0.5 / 2 + (1.0 / 3) / 3 + (1.0 / 6) / 4, 1e-15);
  EXPECT_NEAR(rank.ExpectedRank(), 1 + 0.5 * 1 + 2.0 / 3 + 0.5, 1e-15);
  EXPECT_EQ(rank.RecallAtK(1), 0.0);
  EXPECT_NEAR(rank.RecallAtK(2), 0.5, 1e-15);
  EXPECT_NEAR(rank.RecallAtK(3), 5.0 / 6, 1e-15);
  EXPECT_EQ(rank.RecallAtK(4), 1.0);
}

TEST(FirstTrueRank, MatchesBruteForceOverAllTieOrders) {
  for (int trial = 0; trial < 60; ++trial) {
    Rng rng = KeyedRng(7, "metrics_test.ties", trial);
    const int n = 2 + static_cast<int>(rng.UniformInt(6));  // up to 7 items: 5040 orders
    std::vector<double> scores(n);
    std::vector<uint8_t> is_true(n);
    for (int i = 0; i < n; ++i) {
      scores[i] = static_cast<double>(rng.UniformInt(3));
      is_true[i] = rng.Uniform() < 0.35 ? 1 : 0;
    }
    is_true[rng.UniformInt(n)] = 1;
    double brute_rr = 0;
    std::vector<double> brute_recall(9);
    BruteForce(scores, is_true, &brute_rr, &brute_recall);
    const FirstTrueRank rank = RankFirstTrueMatch(scores, is_true);
    EXPECT_NEAR(rank.ExpectedReciprocalRank(), brute_rr, 1e-12) << "trial " << trial;
    for (int k = 1; k <= 8; ++k) {
      EXPECT_NEAR(rank.RecallAtK(k), brute_recall[k], 1e-12) << "trial " << trial << " k " << k;
    }
  }
}

TEST(ComputeMetrics, AllZeroScoresGiveTheRandomOrderExpectation) {
  // One true match among 10 equal scores: E[1/rank] = H_10 / 10, Recall@5 = 1/2.
  const std::vector<PoseRecord> poses = LinePoses(20);
  std::vector<int> database(10);
  std::iota(database.begin(), database.end(), 0);
  std::vector<uint8_t> is_true(10, 0);
  is_true[7] = 1;
  const MethodMetrics m = ComputeMetrics({MakeQuery(15, database, is_true)}, {std::vector<double>(10, 0.0)}, poses);
  double harmonic = 0;
  for (int k = 1; k <= 10; ++k) harmonic += 1.0 / k;
  EXPECT_NEAR(m.mrr, harmonic / 10, 1e-15);
  EXPECT_NEAR(m.recall_at_1, 0.1, 1e-15);
  EXPECT_NEAR(m.recall_at_5, 0.5, 1e-15);
  EXPECT_NEAR(m.recall_at_10, 1.0, 1e-15);
  ASSERT_EQ(m.queries.size(), 1u);
  EXPECT_EQ(m.queries[0].top1_frame, 0);  // first in database order among the tie
  EXPECT_EQ(m.queries[0].top1_tie_size, 10);
  EXPECT_NEAR(m.queries[0].top1_expected_correct, 0.1, 1e-15);
  EXPECT_NEAR(m.queries[0].first_true_rank, 5.5, 1e-15);
}

TEST(ComputeMetrics, PerfectMethodHasUnitPrAucMrrAndRecallAtFullPrecision) {
  const std::vector<PoseRecord> poses = LinePoses(30);
  std::vector<Query> queries;
  std::vector<std::vector<double>> scores;
  for (int q = 0; q < 5; ++q) {
    queries.push_back(MakeQuery(20 + q, {0, 1, 2, 3}, {0, 0, 1, 0}));
    scores.push_back({1.0, 2.0, 10.0 + q, 0.0});  // the true match always wins, by varying margins
  }
  const MethodMetrics m = ComputeMetrics(queries, scores, poses);
  EXPECT_EQ(m.mrr, 1.0);
  EXPECT_EQ(m.recall_at_1, 1.0);
  EXPECT_EQ(m.pr_auc, 1.0);
  EXPECT_EQ(m.recall_at_100p, 1.0);
  ASSERT_EQ(m.pr_curve.size(), 5u);
  EXPECT_EQ(m.pr_curve.front().threshold, 14.0);
  EXPECT_EQ(m.pr_curve.back().recall, 1.0);
}

TEST(ComputeMetrics, PrCurveAucAndRecallAtFullPrecisionAreHandComputed) {
  // Top-1 scores 10 (correct), 8 (correct), 6 (wrong), 4 (correct). Points (R, P):
  // (1/4, 1), (1/2, 1), (1/2, 2/3), (3/4, 3/4): AUC = 1/4 + 1/4 + 0 + 1/4 * 3/4; R@100%P = 1/2.
  const std::vector<PoseRecord> poses = LinePoses(30);
  const std::vector<Query> queries = {MakeQuery(20, {0, 1}, {1, 0}), MakeQuery(21, {0, 1}, {1, 0}),
                                      MakeQuery(22, {0, 1}, {1, 0}), MakeQuery(23, {0, 1}, {1, 0})};
  const MethodMetrics m = ComputeMetrics(queries, {{10, 1}, {8, 1}, {1, 6}, {4, 1}}, poses);
  ASSERT_EQ(m.pr_curve.size(), 4u);
  EXPECT_NEAR(m.pr_curve[2].precision, 2.0 / 3, 1e-15);
  EXPECT_NEAR(m.pr_curve[2].recall, 0.5, 1e-15);
  EXPECT_NEAR(m.pr_auc, 0.25 + 0.25 + 0.25 * 0.75, 1e-15);
  EXPECT_NEAR(m.recall_at_100p, 0.5, 1e-15);
  EXPECT_NEAR(m.mrr, (1 + 1 + 0.5 + 1) / 4, 1e-15);
  EXPECT_EQ(m.queries[2].top1_frame, 1);
  EXPECT_FALSE(m.queries[2].top1_is_true_match);
  EXPECT_EQ(m.queries[2].top1_distance_m, 21.0);  // query 22 at x = 22, frame 1 at x = 1
  EXPECT_EQ(m.queries[2].first_true_rank, 2.0);
}

TEST(ComputeMetrics, TiedTopOneCountsItsExpectedCorrectnessInPrecision) {
  // Top-1 tied between a true and a false match: the claim is half correct.
  const MethodMetrics m = ComputeMetrics({MakeQuery(5, {0, 1}, {0, 1})}, {{3.0, 3.0}}, LinePoses(6));
  ASSERT_EQ(m.pr_curve.size(), 1u);
  EXPECT_NEAR(m.pr_curve[0].precision, 0.5, 1e-15);
  EXPECT_NEAR(m.pr_curve[0].recall, 0.5, 1e-15);
  EXPECT_EQ(m.recall_at_100p, 0.0);
  EXPECT_NEAR(m.mrr, 0.75, 1e-15);
}

TEST(ComputeMetrics, QueriesWithoutTrueMatchAreSkippedAndCounted) {
  const std::vector<Query> queries = {MakeQuery(10, {0, 1}, {1, 0}, 1), MakeQuery(11, {0, 1}, {0, 0}, 1),
                                      MakeQuery(12, {}, {}, 2), MakeQuery(13, {0, 1}, {0, 1}, 2)};
  const MethodMetrics m = ComputeMetrics(queries, {{2, 1}, {5, 1}, {}, {2, 1}}, LinePoses(20));
  EXPECT_EQ(m.queries_total, 4);
  EXPECT_EQ(m.queries_scored, 2);
  EXPECT_EQ(m.queries_skipped, 2);
  EXPECT_NEAR(m.mrr, (1 + 0.5) / 2, 1e-15);
  ASSERT_EQ(m.per_lap.size(), 2u);
  EXPECT_EQ(m.per_lap.at(1).mrr, 1.0);
  EXPECT_EQ(m.per_lap.at(2).mrr, 0.5);
  EXPECT_EQ(m.per_lap.at(2).queries_scored, 1);
  EXPECT_FALSE(m.queries[1].scored);
  EXPECT_EQ(m.queries[1].top1_frame, 0);  // still recorded for the report
  EXPECT_EQ(m.queries[2].top1_frame, -1);
  const std::string csv = QueryRecordsToCsv(m.queries);
  EXPECT_NE(csv.find("\n12,2,0,0,0,,,,,,,0,,,,\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\n10,1,2,1,1,1,1,0,2,10,1,1,1,1,1,1\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\n13,2,2,1,1,2,0.5,0,2,13,0,1,0,0,1,1\n"), std::string::npos) << csv;  // recall at 1, 5, 10
}

TEST(ComputeMetrics, NoScoredQueryLeavesRatesUndefinedAsJsonNull) {
  const MethodMetrics m = ComputeMetrics({MakeQuery(3, {0}, {0})}, {{1.0}}, LinePoses(4));
  const nlohmann::json j = m.ToJson();
  EXPECT_TRUE(j["mrr"].is_null());
  EXPECT_EQ(j["queries_skipped"], 1);
}

TEST(MethodMetrics, JsonHoldsTheReportKeysAndTiming) {
  MethodMetrics m = ComputeMetrics({MakeQuery(3, {0, 1}, {0, 1})}, {{1.0, 2.0}}, LinePoses(4));
  m.SetTiming({1, 2, 3, 10}, {0.5, 0.5, 0.5, 0.5});
  EXPECT_EQ(m.ms_per_query, 4.5);
  EXPECT_EQ(m.ms_per_query_median, 3.0);
  EXPECT_EQ(m.extract_ms_median, 2.5);
  const nlohmann::json j = m.ToJson();
  for (const char* key : {"mrr", "recall_at_1", "recall_at_5", "recall_at_10", "pr_auc", "recall_at_100p",
                          "ms_per_query", "queries_scored", "queries_skipped", "pr_curve", "per_lap"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["mrr"], 1.0);
  EXPECT_EQ(j["per_lap"]["1"]["mrr"], 1.0);
}

}  // namespace
}  // namespace hoilcd
