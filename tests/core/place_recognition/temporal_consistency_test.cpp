#include "hoilcd/core/place_recognition/temporal_consistency.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "option_properties.h"

namespace hoilcd {
namespace {

// Six consecutive queries (frames 100..105) against database frames 0..19, background score 1.
// Queries 1..4 match database frames 5, 6, 7, 8 (score 10): a consistent forward run. Query 5's
// best is an isolated spike at frame 15 (score 12); its continuation of the run, frame 9, has 3.
struct Table {
  std::vector<int> queries = {100, 101, 102, 103, 104, 105};
  std::vector<int> database;
  std::vector<std::vector<float>> scores;
  Table() : database(20), scores(6, std::vector<float>(20, 1.0f)) {
    for (int j = 0; j < 20; ++j) database[static_cast<size_t>(j)] = j;
    for (int q = 1; q <= 4; ++q) scores[static_cast<size_t>(q)][static_cast<size_t>(q + 4)] = 10;
    scores[5][15] = 12;
    scores[5][9] = 3;
  }
};

TemporalConsistencyOptions Strict() {
  TemporalConsistencyOptions options;
  options.consecutive_queries = 3;
  options.candidates_per_query = 1;
  options.max_frame_gap = 2;
  return options;
}

int Top1(const std::vector<float>& row) {
  return static_cast<int>(std::max_element(row.begin(), row.end()) - row.begin());
}

TEST(TemporalConsistency, ConsistentRunIsKeptAndIsolatedSpikeIsSuppressed) {
  const Table t;
  const auto out = TemporalConsistencyScores(t.queries, t.database, t.scores, Strict());
  // The run is supported from its third query on, with its original score.
  EXPECT_EQ(out[3][7], 10.0f);
  EXPECT_EQ(out[4][8], 10.0f);
  EXPECT_EQ(Top1(out[3]), 7);
  EXPECT_EQ(Top1(out[4]), 8);
  // Its first two queries have no 3-query history yet.
  EXPECT_LT(out[1][5], 0.0f);
  EXPECT_LT(out[2][6], 0.0f);
  // Query 5: the spike drops below the run's continuation.
  EXPECT_EQ(out[5][9], 3.0f);
  EXPECT_LT(out[5][15], out[5][9]);
  EXPECT_EQ(Top1(out[5]), 9);
}

TEST(TemporalConsistency, SupportedCandidatesRankFirstAndEachGroupKeepsItsOrder) {
  const Table t;
  const auto out = TemporalConsistencyScores(t.queries, t.database, t.scores, Strict());
  for (size_t q = 0; q < out.size(); ++q) {
    for (size_t a = 0; a < 20; ++a) {
      for (size_t b = 0; b < 20; ++b) {
        const bool a_kept = out[q][a] == t.scores[q][a];
        const bool b_kept = out[q][b] == t.scores[q][b];
        if (a_kept && !b_kept) {
          EXPECT_GT(out[q][a], out[q][b]);
        }
        if (a_kept == b_kept && t.scores[q][a] > t.scores[q][b]) {
          EXPECT_GT(out[q][a], out[q][b]);
        }
      }
    }
  }
}

TEST(TemporalConsistency, OneConsecutiveQueryLeavesScoresUnchanged) {
  const Table t;
  TemporalConsistencyOptions options = Strict();
  options.consecutive_queries = 1;
  EXPECT_EQ(TemporalConsistencyScores(t.queries, t.database, t.scores, options), t.scores);
}

TEST(TemporalConsistency, GapBetweenQueriesBreaksTheChain) {
  Table t;
  t.queries = {100, 101, 102, 110, 111, 112};  // query 3 comes 8 frames after query 2
  const auto out = TemporalConsistencyScores(t.queries, t.database, t.scores, Strict());
  EXPECT_LT(out[3][7], 0.0f);
  EXPECT_LT(out[4][8], 0.0f);
  EXPECT_EQ(out[5][9], 3.0f);  // queries 3, 4, 5 are consecutive again: frames 7, 8, 9
}

TEST(TemporalConsistency, BackwardRunIsNotConsistent) {
  Table t;
  for (auto& row : t.scores) std::fill(row.begin(), row.end(), 1.0f);
  for (int q = 1; q <= 4; ++q) t.scores[static_cast<size_t>(q)][static_cast<size_t>(12 - q)] = 10;
  const auto out = TemporalConsistencyScores(t.queries, t.database, t.scores, Strict());
  for (size_t q = 1; q <= 4; ++q) EXPECT_LT(out[q][12 - q], t.scores[q][12 - q]);  // demoted
}

TEST(TemporalConsistency, MoreCandidatesPerQueryLetASecondBestChainSupport) {
  // Query 2's best is a spike elsewhere; the run 5, 6, 7 passes through its second best.
  Table t;
  t.scores[2][17] = 20;
  TemporalConsistencyOptions options = Strict();
  EXPECT_LT(TemporalConsistencyScores(t.queries, t.database, t.scores, options)[3][7], 0.0f);
  options.candidates_per_query = 2;
  EXPECT_EQ(TemporalConsistencyScores(t.queries, t.database, t.scores, options)[3][7], 10.0f);
}

TEST(TemporalConsistency, OptionChecksNameTheBadField) {
  TemporalConsistencyOptions options;
  EXPECT_EQ(options.Check(), "");
  options.consecutive_queries = 0;
  EXPECT_NE(options.Check().find("consecutive_queries"), std::string::npos);
  options = TemporalConsistencyOptions();
  options.candidates_per_query = 0;
  EXPECT_NE(options.Check().find("candidates_per_query"), std::string::npos);
  options = TemporalConsistencyOptions();
  options.max_frame_gap = -1;
  EXPECT_NE(options.Check().find("max_frame_gap"), std::string::npos);
  options = TemporalConsistencyOptions();
  options.max_query_gap = 0;
  EXPECT_NE(options.Check().find("max_query_gap"), std::string::npos);
}

TEST(TemporalConsistency, OptionsHoldTheirTablesDefaultsAndEveryBoundIsChecked) {
  ExpectConstructedHoldsTheTableDefaults<TemporalConsistencyOptions>();
  EXPECT_EQ(ExpectEveryBoundCrossedIsNamedByCheck<TemporalConsistencyOptions>(), 8);
}

TEST(TemporalConsistency, UnsortedFramesAreRejected) {
  const Table t;
  std::vector<int> unsorted = t.queries;
  std::swap(unsorted[0], unsorted[1]);
  EXPECT_THROW(TemporalConsistencyScores(unsorted, t.database, t.scores, Strict()), std::logic_error);
}

}  // namespace
}  // namespace hoilcd
