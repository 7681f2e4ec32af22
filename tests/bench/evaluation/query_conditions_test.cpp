#include "hoilcd/bench/evaluation/query_conditions.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <gtest/gtest.h>

#include "hoilcd/bench/evaluation/evaluate.h"
#include "recording_runs.h"
#include "test_dir.h"
#include "tiny_room.h"

namespace hoilcd {
namespace {

// E[1 / rank of the first true match] over every order of D items with t true, by enumeration.
double BruteForceChance(int d, int t) {
  std::vector<int> order(d, 0);
  std::fill(order.begin(), order.begin() + t, 1);
  std::sort(order.begin(), order.end());
  double sum = 0;
  int count = 0;
  do {
    const int first = static_cast<int>(std::find(order.begin(), order.end(), 1) - order.begin());
    sum += 1.0 / (first + 1);
    ++count;
  } while (std::next_permutation(order.begin(), order.end()));
  return sum / count;
}

TEST(QueryConditions, ChanceIsTheExpectedReciprocalRankOfARandomOrder) {
  for (const auto& [d, t] : std::vector<std::pair<int, int>>{{1, 1}, {5, 1}, {5, 2}, {7, 3}, {8, 8}}) {
    EXPECT_NEAR(ChanceReciprocalRank(d, t), BruteForceChance(d, t), 1e-12) << d << " " << t;
  }
  EXPECT_NEAR(ChanceReciprocalRank(4, 1), (1 + 0.5 + 1 / 3.0 + 0.25) / 4, 1e-12);
  EXPECT_TRUE(std::isnan(ChanceReciprocalRank(5, 0)));
}

TEST(QueryConditions, EachQueryFallsInTheStratumItsConditionsName) {
  QueryConditions c;
  c.person_pixels = 0;
  c.blank = true;
  EXPECT_EQ(StratumOf("view", c), "blank view");
  c.blank = false;
  EXPECT_EQ(StratumOf("view", c), "static structure only");
  c.people_in_view = 2;
  c.mean_occlusion = 0.3;
  EXPECT_EQ(StratumOf("view", c), "1-2 people");
  EXPECT_EQ(StratumOf("occlusion", c), "people 25-50 % occluded");
  c.people_in_view = 3;
  EXPECT_EQ(StratumOf("view", c), "3 or more people");
  c.people_in_view = 0;
  c.person_pixels = -1;  // no EXR: a blank view cannot be told from structure
  EXPECT_EQ(StratumOf("view", c), "no people");
  EXPECT_EQ(StratumOf("occlusion", c), "");  // nobody to be occluded
  c.lap = 1;
  EXPECT_EQ(StratumOf("lap", c), "lap 2");
  c.walkers_in_view = 1;
  EXPECT_EQ(StratumOf("walkers", c), "walker in view");
}

TEST(QueryConditions, StrataHoldTheMetricsOfTheirOwnQueriesAndChance) {
  // Four queries: two blank (ranks 4 and 2), two with 3 people (rank 1 each); databases of 4, one true.
  std::vector<QueryConditions> conditions(4);
  std::vector<QueryRecord> records(4);
  const double rr[] = {0.25, 0.5, 1, 1};
  for (int i = 0; i < 4; ++i) {
    conditions[i].person_pixels = i < 2 ? 0 : 100;
    conditions[i].blank = i < 2;
    conditions[i].people_in_view = i < 2 ? 0 : 3;
    conditions[i].mean_occlusion = i < 2 ? NAN : 0.1;
    records[i].frame = i;
    records[i].scored = true;
    records[i].reciprocal_rank = rr[i];
    records[i].recall_at_1 = rr[i] == 1;
    records[i].database_size = 4;
    records[i].true_matches = 1;
    records[i].top1_score = rr[i];
    records[i].top1_expected_correct = rr[i] == 1;
  }
  const std::vector<StratumRow> rows = Stratify(conditions, {"m"}, {&records}, {"view", "occlusion"});
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].stratum, "blank view");
  EXPECT_EQ(rows[0].queries, 2);
  EXPECT_DOUBLE_EQ(rows[0].mrr[0], 0.375);
  EXPECT_DOUBLE_EQ(rows[0].recall_at_1[0], 0);
  EXPECT_DOUBLE_EQ(rows[0].chance_mrr, ChanceReciprocalRank(4, 1));
  EXPECT_EQ(rows[1].stratum, "3 or more people");
  EXPECT_DOUBLE_EQ(rows[1].mrr[0], 1);
  EXPECT_EQ(rows[2].stratification, "occlusion");
  EXPECT_EQ(rows[2].queries, 2);
  const nlohmann::json json = StrataJson(rows);
  EXPECT_EQ(json[0]["methods"]["m"]["mrr"], 0.375);
}

TEST(QueryConditions, ConditionsAgreeWithTheDatasetsGroundTruth) {
  const test::TestDir temp;
  const Dataset dataset = test::TinyRoomDataset(temp / "dataset");
  const Labelling labelling = LabelQueries(dataset, ProtocolOptions());
  const std::vector<QueryConditions> one = ComputeQueryConditions(dataset, labelling.queries, 1);
  ASSERT_EQ(one.size(), labelling.queries.size());
  int blank = 0, people = 0;
  for (size_t i = 0; i < one.size(); ++i) {
    const QueryConditions& c = one[i];
    EXPECT_EQ(c.frame, labelling.queries[i].frame);
    int in_view = 0;
    for (const PersonRecord& p : dataset.persons()[c.frame].persons) in_view += p.visible_fraction > 0;
    EXPECT_EQ(c.people_in_view, in_view);
    EXPECT_GE(c.person_pixels, 0);  // the dataset has EXRs
    EXPECT_GE(c.temperature_spread_k, 0);
    if (c.blank) {
      EXPECT_EQ(c.person_pixels, 0);
      EXPECT_LT(c.temperature_spread_k, kBlankSpreadK);
    }
    if (labelling.queries[i].NumTrueMatches() > 0) {
      EXPECT_LE(c.nearest_true_distance_m, 0.2 + 1e-9);
    }
    blank += c.blank;
    people += c.people_in_view > 0;
  }
  EXPECT_GT(people, 0);
  // The same at any thread count.
  const std::vector<QueryConditions> two = ComputeQueryConditions(dataset, labelling.queries, 2);
  for (size_t i = 0; i < one.size(); ++i) EXPECT_EQ(ConditionsCsvRow(one[i]), ConditionsCsvRow(two[i]));
  (void)blank;
}

// A run's first frame turns as fast as the frames after it say: the frame before it is another
// run's, hours earlier.
TEST(QueryConditions, TheTurnRateOfARunsFirstFrameIsMeasuredWithinItsRun) {
  const test::TestDir temp;
  const Dataset dataset = test::TinyRoomTwoRuns(temp.str(), 60);
  ProtocolOptions runs;
  runs.protocol = "runs";
  const Labelling labelling = LabelQueries(dataset, runs);
  ASSERT_EQ(labelling.queries.front().frame, 60);
  const QueryConditions c = ComputeQueryConditions(dataset, {labelling.queries.front()}).front();
  const PoseRecord &first = dataset.poses()[60], &next = dataset.poses()[61];
  const double expected_deg_s =
      std::abs(std::remainder(next.theta_rad - first.theta_rad, 2 * M_PI)) * 180 / M_PI / (next.time_s - first.time_s);
  EXPECT_GT(expected_deg_s, 0);
  EXPECT_DOUBLE_EQ(c.turn_rate_deg_s, expected_deg_s);
}

}  // namespace
}  // namespace hoilcd
