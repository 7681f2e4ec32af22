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
  EXPECT_DOUBLE_EQ(d.methods[0].mrr_with_hoi, 0.75);  // slcd: (1 + 0.5) / 2
  EXPECT_DOUBLE_EQ(d.methods[0].mrr_without_hoi, 1.0);
  EXPECT_DOUBLE_EQ(d.methods[1].mrr_with_hoi, 0.75);  // dlcd: (0.5 + 1) / 2
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

// FourQueries with dlcd-oracle (MRR 0.375, below dlcd's 0.5) and slcd-ideal (MRR 1, above slcd's
// 0.875) and the paired intervals the runner would have added.
BenchResult WithOracles() {
  BenchResult result = FourQueries();
  result.runs.push_back(Run("dlcd-oracle", {0.25, 0.5, 0.5, 0.25}));
  result.runs.push_back(Run("slcd-ideal", {1.0, 1.0, 1.0, 1.0}));
  PairedComparison dlcd;  // written better first: dlcd > dlcd-oracle
  dlcd.a = "dlcd", dlcd.b = "dlcd-oracle", dlcd.delta = 0.125, dlcd.interval = {-0.05, 0.2};
  PairedComparison slcd;
  slcd.a = "slcd-ideal", slcd.b = "slcd", slcd.delta = 0.125, slcd.interval = {0.02, 0.25};
  result.comparisons = {dlcd, slcd};
  return result;
}

TEST(Diagnosis, OraclesSayWhatTheyIsolateFromTheirNumbers) {
  const BenchResult result = WithOracles();
  const Diagnosis d = Diagnose(result);
  ASSERT_EQ(d.oracles.size(), 2u);
  const OracleDiagnosis& dlcd = d.oracles[0];
  EXPECT_EQ(dlcd.oracle, "dlcd-oracle");
  EXPECT_DOUBLE_EQ(dlcd.oracle_mrr, 0.375);
  EXPECT_DOUBLE_EQ(dlcd.method_mrr, 0.5);
  EXPECT_DOUBLE_EQ(dlcd.delta, -0.125);  // oriented oracle - method
  EXPECT_DOUBLE_EQ(dlcd.interval.low, -0.2);
  EXPECT_FALSE(dlcd.helps);
  EXPECT_EQ(dlcd.finding,
            "dlcd-oracle (ground-truth people) 0.375 vs dlcd 0.500 (\xce\x94 -0.125 [-0.200, 0.050]): within the "
            "noise: detection is not DLCD's deficit; the HOI landmarks themselves limit it");
  const OracleDiagnosis& slcd = d.oracles[1];
  EXPECT_TRUE(slcd.helps);
  EXPECT_NE(slcd.finding.find("slcd-ideal (noise-free image) 1.000 vs slcd 0.875 (\xce\x94 +0.125 [0.020, 0.250]): "
                              "higher beyond the noise: the sensor (noise, fixed pattern, blur, drift, FFC) is "
                              "part of SLCD's deficit"),
            std::string::npos)
      << slcd.finding;
  const std::string md = DiagnosisMarkdown(result, d);
  EXPECT_NE(md.find("**Oracles.**"), std::string::npos) << md;
  EXPECT_NE(md.find("- " + dlcd.finding + ".\n"), std::string::npos) << md;
  const nlohmann::json j = d.ToJson();
  EXPECT_DOUBLE_EQ(j["oracles"]["slcd-ideal"]["delta_mrr"].get<double>(), 0.125);
  EXPECT_EQ(j["oracles"]["dlcd-oracle"]["replaced_part_costs_method"], false);
  EXPECT_EQ(j["oracles"]["dlcd-oracle"]["finding"], dlcd.finding);
}

TEST(Diagnosis, AnOracleBelowItsIntervalIsLowerAndOneClearlyAboveSaysThePartCostsTheMethod) {
  BenchResult result = WithOracles();
  result.comparisons[0].interval = {0.01, 0.1};  // dlcd - oracle: now the oracle is separated below
  const Diagnosis d = Diagnose(result);
  EXPECT_NE(d.oracles[0].finding.find("-0.010]): lower: detection is not DLCD's deficit"), std::string::npos)
      << d.oracles[0].finding;
  result.runs[3] = hoilcd::Run("dlcd-oracle", {1.0, 1.0, 1.0, 1.0});
  result.comparisons.clear();  // no interval: a difference of 0.01 or more counts
  const Diagnosis better = Diagnose(result);
  EXPECT_TRUE(better.oracles[0].helps);
  EXPECT_NE(better.oracles[0].finding.find(
                "(\xce\x94 +0.500): higher beyond the noise: detection and tracking are part of DLCD's deficit"),
            std::string::npos)
      << better.oracles[0].finding;
}

TEST(Diagnosis, WithoutOraclesThereIsNoOracleText) {
  const BenchResult result = FourQueries();
  const Diagnosis d = Diagnose(result);
  EXPECT_TRUE(d.oracles.empty());
  EXPECT_EQ(DiagnosisMarkdown(result, d).find("Oracles"), std::string::npos);
  EXPECT_FALSE(d.ToJson().contains("oracles"));
}

TEST(Diagnosis, AnOracleAloneOrLeftOutIsStillReported) {
  BenchResult result;
  result.runs = {hoilcd::Run("slcd-ideal", {1.0, 0.5})};
  result.skipped = {"dlcd-oracle: not run, the dataset has no exr output"};
  const Diagnosis d = Diagnose(result);
  ASSERT_TRUE(d.evaluated);
  EXPECT_FALSE(d.hoi_split);
  const std::string md = DiagnosisMarkdown(result, d);
  EXPECT_NE(md.find("slcd-ideal (noise-free image) 0.750; run slcd beside it"), std::string::npos) << md;
  EXPECT_NE(md.find("- dlcd-oracle: not run, the dataset has no exr output.\n"), std::string::npos) << md;
  EXPECT_EQ(md.find("HOI points |"), std::string::npos) << md;  // no HOI split without dlcd
  EXPECT_FALSE(d.ToJson().contains("queries_with_hoi_points"));
}

}  // namespace
}  // namespace hoilcd
