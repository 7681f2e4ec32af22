#include "hoilcd/bench/report/diagnosis.h"

#include <gtest/gtest.h>

namespace hoilcd {
namespace {

QueryRecord Scored(int frame, double reciprocal_rank, bool top1_true) {
  QueryRecord q;
  q.frame = frame;
  q.scored = true;
  q.reciprocal_rank = reciprocal_rank;
  q.top1_is_true_match = top1_true;
  return q;
}

MethodRun Run(const std::string& name, const std::vector<double>& reciprocal_ranks) {
  MethodRun run;
  run.name = name;
  double sum = 0;
  for (size_t i = 0; i < reciprocal_ranks.size(); ++i) {
    run.metrics.queries.push_back(Scored(static_cast<int>(i), reciprocal_ranks[i], reciprocal_ranks[i] == 1.0));
    sum += reciprocal_ranks[i];
  }
  run.metrics.mrr = sum / reciprocal_ranks.size();
  return run;
}

// Four queries: frames 0 and 1 have HOI points, 2 and 3 none.
BenchResult FourQueries() {
  BenchResult result;
  result.features.resize(4);
  result.features[0].hoi.resize(2);
  result.features[1].hoi.resize(1);
  result.mean_hoi_points_per_frame = 0.75;
  result.ground_truth_person_views = 10;
  result.runs = {Run("slcd", {1.0, 0.5, 1.0, 1.0}), Run("dlcd", {0.5, 1.0, 0.25, 0.25}),
                 Run("fusion", {0.5, 1.0, 0.5, 1.0})};
  return result;
}

TEST(Diagnosis, SplitsEachMethodsMrrByWhetherTheQueryHasHoiPoints) {
  const Diagnosis d = Diagnose(FourQueries());
  ASSERT_TRUE(d.evaluated);
  EXPECT_EQ(d.queries_with_hoi, 2);
  EXPECT_EQ(d.queries_without_hoi, 2);
  ASSERT_EQ(d.methods.size(), 3u);
  EXPECT_DOUBLE_EQ(d.methods[0].mrr_with_hoi, 0.75);     // slcd: (1 + 0.5) / 2
  EXPECT_DOUBLE_EQ(d.methods[0].mrr_without_hoi, 1.0);
  EXPECT_DOUBLE_EQ(d.methods[1].mrr_with_hoi, 0.75);     // dlcd: (0.5 + 1) / 2
  EXPECT_DOUBLE_EQ(d.methods[1].mrr_without_hoi, 0.25);
}

TEST(Diagnosis, CountsQueriesWhereFusionRanksTheTrueMatchBelowTheBetterMethod) {
  const Diagnosis d = Diagnose(FourQueries());
  ASSERT_TRUE(d.fusion.has_value());
  EXPECT_EQ(d.fusion->better, "slcd");
  EXPECT_EQ(d.fusion->weaker, "dlcd");
  EXPECT_EQ(d.fusion->queries_ranked_lower, 2);                    // queries 0 and 2
  EXPECT_EQ(d.fusion->queries_ranked_lower_weaker_top1_false, 2);  // dlcd's top-1 false on both
  EXPECT_EQ(d.fusion->queries_ranked_higher, 1);                   // query 1
}

TEST(Diagnosis, JsonHoldsTheNumbersTheMarkdownPrints) {
  const BenchResult result = FourQueries();
  const Diagnosis d = Diagnose(result);
  const nlohmann::json j = d.ToJson();
  EXPECT_EQ(j["queries_with_hoi_points"], 2);
  EXPECT_DOUBLE_EQ(j["methods"]["dlcd"]["mrr_without_hoi_points"].get<double>(), 0.25);
  EXPECT_EQ(j["fusion"]["queries_ranked_lower"], 2);
  const std::string md = DiagnosisMarkdown(result, d);
  EXPECT_NE(md.find("| dlcd | 0.750 | 0.250 |"), std::string::npos) << md;
  EXPECT_NE(md.find("fusion ranks the true match lower than slcd on 2 queries"), std::string::npos) << md;
}

TEST(Diagnosis, WithoutDlcdThereIsNothingToDiagnose) {
  BenchResult result = FourQueries();
  result.runs.erase(result.runs.begin() + 1);
  const Diagnosis d = Diagnose(result);
  EXPECT_FALSE(d.evaluated);
  EXPECT_EQ(DiagnosisMarkdown(result, d), "");
}

TEST(Diagnosis, MrrOfAnEmptyGroupIsNullInJson) {
  BenchResult result = FourQueries();
  result.features[2].hoi.resize(1);
  result.features[3].hoi.resize(1);
  const nlohmann::json j = Diagnose(result).ToJson();
  EXPECT_TRUE(j["methods"]["slcd"]["mrr_without_hoi_points"].is_null());
  EXPECT_EQ(j["queries_without_hoi_points"], 0);
}

}  // namespace
}  // namespace hoilcd
