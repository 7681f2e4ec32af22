#include "hoilcd/bench/evaluation/evaluate.h"

#include <cmath>

#include <gtest/gtest.h>

#include "hoilcd/bench/methods/methods.h"
#include "hoilcd/bench/runner/runner.h"
#include "hoilcd/sim/output/sequence.h"
#include "input_error_of.h"
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
    const ScoreMatrix m =
        ScoresFromCsv(ScoresToCsv(result.queries, run.scores), run.name + ".csv", dataset.num_frames());
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
              std::string::npos)
        << e.what();
  }
}

TEST(Evaluate, ADatasetWithoutATrueMatchIsAnErrorSayingWhyMrrIsUndefined) {
  const test::TestDir temp;
  // 150 frames of the tiny room: three quarters of a lap, no revisit.
  const Dataset dataset = test::TinyRoomDataset(temp / "short", {"frames=150"});
  ScoreMatrix m = ScoreMatrix::Unscored(dataset.num_frames());
  m.values.assign(m.values.size(), 1.0);
  ProtocolOptions laps;
  std::string error = test::InputErrorOf([&] { Evaluate(dataset, m, "x", laps); });
  EXPECT_NE(error.find(dataset.dir() + ": no query has a true match, so MRR, Recall@K and PR are undefined: the laps "
                                       "protocol queries the laps after the first, and the 150 frames never complete "
                                       "a first lap (the odometric heading turns "),
            std::string::npos)
      << error;
  EXPECT_NE(error.find("render more frames, or use --protocol revisit"), std::string::npos) << error;
  ProtocolOptions revisit;
  revisit.protocol = "revisit";
  error = test::InputErrorOf([&] { Evaluate(dataset, m, "x", revisit); });
  EXPECT_NE(error.find("no frame comes back within 0.2 m of a frame more than 10 s older by the odometric poses"),
            std::string::npos)
      << error;
  EXPECT_EQ(NoTrueMatchReason(LabelQueries(TinyDataset(temp), laps)), "");
}

// A numpy object array of None reaches Evaluate as an all-NaN matrix (Python's forcecast).
TEST(Evaluate, ScoresOfNoPairTheProtocolRanksAreAnErrorNotARandomOrdersMetrics) {
  const test::TestDir temp;
  const Dataset dataset = TinyDataset(temp);
  ScoreMatrix m = ScoreMatrix::Unscored(dataset.num_frames());
  m.source = "scores.npy";
  const std::string error = test::InputErrorOf([&] { Evaluate(dataset, m, "x", ProtocolOptions{}); });
  EXPECT_NE(error.find("scores.npy: scores none of the "), std::string::npos) << error;
  EXPECT_NE(error.find(" queries with a true match: expected scores of those pairs"), std::string::npos) << error;
  m.At(0, 1) = 5;  // a pair no query ranks: frame 0 is in the first lap, never a query
  EXPECT_NE(test::InputErrorOf([&] { Evaluate(dataset, m, "x", ProtocolOptions{}); }).find("scores none of the "),
            std::string::npos);
}

TEST(Evaluate, QueriesWithNoScoredPairAreCountedInAWarning) {
  const test::TestDir temp;
  const Dataset dataset = TinyDataset(temp);
  const ProtocolOptions protocol;
  const Labelling labelling = LabelQueries(dataset, protocol);
  ScoreMatrix m = ScoreMatrix::Unscored(dataset.num_frames());
  m.source = "half.csv";
  int worth_scoring = 0, scored = 0;
  for (size_t i = 0; i < labelling.queries.size(); ++i) {
    if (!labelling.to_score[i]) continue;
    if (worth_scoring++ % 2 == 0) {
      ++scored;
      for (int r : labelling.queries[i].database) m.At(labelling.queries[i].frame, r) = r;
    }
  }
  ASSERT_GT(worth_scoring, 2);
  const MethodReport r = Evaluate(dataset, m, "half", protocol);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_EQ(r.warnings[0], "half.csv: " + std::to_string(worth_scoring - scored) + " of the " +
                               std::to_string(worth_scoring) +
                               " queries with a true match have no scored pair in "
                               "their database; each ranks it all tied (the expected rank of a random order)");
  for (const Query& q : labelling.queries) {
    for (int r : q.database) m.At(q.frame, r) = 1;
  }
  EXPECT_TRUE(Evaluate(dataset, m, "full", protocol).warnings.empty());
}

TEST(Evaluate, AnInfiniteScoreIsAnErrorNamingTheScoresSource) {
  const test::TestDir temp;
  const Dataset dataset = TinyDataset(temp);
  const Labelling labelling = LabelQueries(dataset, ProtocolOptions{});
  ScoreMatrix m = ScoreMatrix::Unscored(dataset.num_frames());
  m.source = "inf.npy";
  const Query& q = labelling.queries.back();
  m.At(q.frame, q.database[0]) = INFINITY;
  EXPECT_NE(test::InputErrorOf([&] { Evaluate(dataset, m, "x", ProtocolOptions{}); })
                .find("inf.npy: pair query " + std::to_string(q.frame) + ", reference " +
                      std::to_string(q.database[0]) + " is infinite"),
            std::string::npos);
}

// Python's matrices reach Evaluate without a reader's checks.
TEST(Evaluate, AScoreBeyond1e300IsAnErrorNotAnInternalOne) {
  const test::TestDir temp;
  const Dataset dataset = TinyDataset(temp);
  const Labelling labelling = LabelQueries(dataset, ProtocolOptions{});
  ScoreMatrix m = ScoreMatrix::Unscored(dataset.num_frames());
  const Query& q = labelling.queries.back();
  for (int r : q.database) m.At(q.frame, r) = 1;
  m.At(q.frame, q.database[0]) = NAN;     // unscored: ranked below the lowest score...
  m.At(q.frame, q.database[1]) = -1e308;  // ...which leaves no finite value below it
  EXPECT_NE(test::InputErrorOf([&] { Evaluate(dataset, m, "x", ProtocolOptions{}); })
                .find("scores: pair query " + std::to_string(q.frame) + ", reference " + std::to_string(q.database[1]) +
                      " is -1e+308: expected a score of magnitude at most 1e300, or NaN for unscored"),
            std::string::npos);
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
