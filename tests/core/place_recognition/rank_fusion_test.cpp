#include "hoilcd/core/place_recognition/rank_fusion.h"

#include <limits>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

namespace hoilcd {
namespace {

TEST(ReciprocalRankFusion, KZeroOnTwoRankingsGivesTheHandComputedScoresAndOrder) {
  // SLCD ranks 2,0,1,3 and DLCD ranks 1,2,3,0; item 4 appears in neither.
  const std::vector<std::vector<int>> rankings = {{2, 0, 1, 3}, {1, 2, 3, 0}};
  const std::vector<double> scores = ReciprocalRankFusion(rankings, 5);
  ASSERT_EQ(scores.size(), 5u);
  EXPECT_DOUBLE_EQ(scores[0], 1.0 / 2 + 1.0 / 4);
  EXPECT_DOUBLE_EQ(scores[1], 1.0 / 3 + 1.0 / 1);
  EXPECT_DOUBLE_EQ(scores[2], 1.0 / 1 + 1.0 / 2);
  EXPECT_DOUBLE_EQ(scores[3], 1.0 / 4 + 1.0 / 3);
  EXPECT_DOUBLE_EQ(scores[4], 0.0);
  EXPECT_EQ(RankByScore(scores), (std::vector<int>{2, 1, 0, 3, 4}));
}

TEST(ReciprocalRankFusion, KShiftsEveryRankAndAbsentItemsContributeNothing) {
  const std::vector<std::vector<int>> rankings = {{0, 1}, {1}};
  const std::vector<double> scores = ReciprocalRankFusion(rankings, 3, 60.0);
  EXPECT_DOUBLE_EQ(scores[0], 1.0 / 61);
  EXPECT_DOUBLE_EQ(scores[1], 1.0 / 62 + 1.0 / 61);
  EXPECT_DOUBLE_EQ(scores[2], 0.0);
}

TEST(ReciprocalRankFusion, InvalidRankingsAreRejected) {
  EXPECT_THROW(ReciprocalRankFusion({{0, 3}}, 3), std::logic_error);     // index out of range
  EXPECT_THROW(ReciprocalRankFusion({{0, -1}}, 3), std::logic_error);    // negative index
  EXPECT_THROW(ReciprocalRankFusion({{1, 1}}, 3), std::logic_error);     // listed twice
  EXPECT_THROW(ReciprocalRankFusion({{0}}, 3, -1.0), std::logic_error);  // 1/(k + 1) infinite
  EXPECT_NO_THROW(ReciprocalRankFusion({{1}, {1}}, 3));                  // once per ranking is fine
}

TEST(RankByScore, SortsDescendingAndKeepsTiesInIndexOrder) {
  EXPECT_EQ(RankByScore({1, 3, 3, 0, 1}), (std::vector<int>{1, 2, 0, 4, 3}));
  EXPECT_TRUE(RankByScore({}).empty());
  EXPECT_THROW(RankByScore({1, std::numeric_limits<double>::quiet_NaN()}), std::logic_error);
}

}  // namespace
}  // namespace hoilcd

namespace hoilcd {
namespace {

TEST(FractionalRanks, TiedItemsShareTheMeanOfTheirPositions) {
  const std::vector<double> ranks = FractionalRanks({5, 0, 5, 0, 0, 9});
  // Order: 9 (rank 1), the two 5s (ranks 2, 3 -> 2.5), the three 0s (ranks 4..6 -> 5).
  EXPECT_EQ(ranks, (std::vector<double>{2.5, 5, 2.5, 5, 5, 1}));
}

TEST(ReciprocalRankFusionOfScores, EqualsRankFusionWithoutTiesAndIgnoresDatabaseOrderWithTies) {
  const std::vector<double> a = {3, 1, 2}, b = {1, 3, 2};
  const std::vector<double> fused = ReciprocalRankFusionOfScores({a, b}, 0.0);
  const std::vector<double> reference = ReciprocalRankFusion({RankByScore(a), RankByScore(b)}, 3, 0.0);
  for (int i = 0; i < 3; ++i) EXPECT_DOUBLE_EQ(fused[i], reference[i]);
  // All-tied lists give every item the same fused score, whatever the order.
  const std::vector<double> tied = ReciprocalRankFusionOfScores({{0, 0, 0}, {0, 0, 0}}, 0.0);
  EXPECT_DOUBLE_EQ(tied[0], tied[2]);
  EXPECT_DOUBLE_EQ(tied[0], 2.0 / 2.0);
}

}  // namespace
}  // namespace hoilcd
