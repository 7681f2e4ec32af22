#include "hoilcd/bench/evaluation/evaluate.h"

#include <gtest/gtest.h>

#include <cmath>

#include "hoilcd/bench/methods/methods.h"
#include "hoilcd/bench/runner/runner.h"
#include "hoilcd/sim/output/sequence.h"
#include "test_dir.h"
#include "tiny_room.h"

namespace hoilcd {
namespace {

Dataset TinyDataset(const test::TestDir& temp) { return test::TinyRoomDataset(temp / "dataset"); }

TEST(Evaluate, EveryMethodsScoresThroughACsvFileReproduceItsMetricsExactly) {
  const test::TestDir temp;
  const Dataset dataset = TinyDataset(temp);
  BenchOptions options;
  options.methods = DefaultMethods();
  const BenchResult result = RunBench(dataset, options);
  for (const MethodRun& run : result.runs) {
    const ScoreMatrix m = ScoresFromCsv(ScoresToCsv(result.queries, run.scores), run.name + ".csv", dataset.num_frames());
    const MethodReport r = Evaluate(dataset, m, run.name, options.protocol);
    EXPECT_EQ(r.metrics.mrr, run.metrics.mrr) << run.name;
    EXPECT_EQ(r.metrics.recall_at_1, run.metrics.recall_at_1) << run.name;
    EXPECT_EQ(r.metrics.pr_auc, run.metrics.pr_auc) << run.name;
    EXPECT_EQ(r.other_metrics.mrr, run.other_metrics.mrr) << run.name;
    EXPECT_EQ(r.metrics.queries_scored, run.metrics.queries_scored) << run.name;
  }
}

TEST(Evaluate, UnscoredPairsRankBelowEveryScoredOneSoScoringOnlyTrueMatchesGivesMrrOne) {
  const test::TestDir temp;
  const Dataset dataset = TinyDataset(temp);
  ProtocolOptions protocol;
  const Labelling labelling = LabelQueries(dataset, protocol);
  ScoreMatrix m = ScoreMatrix::Unscored(dataset.num_frames());
  for (const Query& q : labelling.queries) {
    for (size_t j = 0; j < q.database.size(); ++j)
      if (q.is_true_match[j]) m.At(q.frame, q.database[j]) = -5.0;  // low, but scored
  }
  const MethodReport r = Evaluate(dataset, m, "oracle", protocol);
  ASSERT_GT(r.metrics.queries_scored, 0);
  EXPECT_EQ(r.metrics.mrr, 1.0);
  EXPECT_EQ(r.metrics.recall_at_1, 1.0);
  const nlohmann::json j = EvaluateReportJson(dataset, protocol, r, "an oracle");
  EXPECT_EQ(j["methods"]["oracle"]["mrr"].get<double>(), 1.0);
  EXPECT_EQ(j["methods"]["oracle"]["description"], "an oracle");
  EXPECT_TRUE(j["other_ground_truth"]["methods"]["oracle"].contains("mrr"));
}

TEST(Evaluate, AMatrixOfTheWrongSizeIsAnErrorNamingBothSizes) {
  const test::TestDir temp;
  const Dataset dataset = TinyDataset(temp);
  try {
    Evaluate(dataset, ScoreMatrix::Unscored(3), "x", ProtocolOptions{});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("a 3 x 3 matrix: expected " + std::to_string(dataset.num_frames())),
              std::string::npos) << e.what();
  }
}

TEST(Evaluate, ANameThatIsNotUtf8GoesIntoTheReportJsonEscaped) {
  const test::TestDir temp;
  const Dataset dataset = TinyDataset(temp);
  const ProtocolOptions protocol;
  const Labelling labelling = LabelQueries(dataset, protocol);
  ScoreMatrix m = ScoreMatrix::Unscored(dataset.num_frames());
  for (const Query& q : labelling.queries) {
    for (int r : q.database) m.At(q.frame, r) = 1;
  }
  const MethodReport r = Evaluate(dataset, m, "caf\xe9\n", protocol);
  EXPECT_EQ(r.name, "caf\\xe9\\x0a");
  const nlohmann::json j = EvaluateReportJson(dataset, protocol, r, "scores from caf\xe9.csv");
  EXPECT_NO_THROW(j.dump());
  EXPECT_EQ(j["methods"]["caf\\xe9\\x0a"]["description"], "scores from caf\\xe9.csv");
}

}  // namespace
}  // namespace hoilcd
