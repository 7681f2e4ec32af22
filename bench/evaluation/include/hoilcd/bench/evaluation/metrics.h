// Retrieval metrics of one loop-closure method from per-query scores (higher = better): MRR,
// Recall@K, the top-1 precision-recall curve, PR-AUC and recall at 100 % precision. Ties are
// never broken by database order: every rank figure is its expectation over a uniformly random
// order of the tied items, computed exactly.
#pragma once

#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hoilcd/bench/evaluation/protocol.h"
#include "hoilcd/core/dataset/dataset.h"

namespace hoilcd {

// Where the first true match lands in one query's ranking.
struct FirstTrueRank {
  int above = 0;     // items scoring strictly higher than the best-scoring true match (all false)
  int tie_size = 0;  // items with exactly the best true match's score (g), itself included
  int tie_true = 0;  // true matches among them (t >= 1)

  double ExpectedRank() const;            // s + (g + 1) / (t + 1), 1-based
  double ExpectedReciprocalRank() const;  // E[1 / (s + k)], k = first true position in the group
  double RecallAtK(int k) const;          // P(first true match within the top k)
};

// HOILCD_CHECK: same sizes, finite scores, at least one true match.
FirstTrueRank RankFirstTrueMatch(const std::vector<double>& scores, const std::vector<uint8_t>& is_true_match);

// One row of queries.csv.
struct QueryRecord {
  int frame = 0;
  int lap = 0;
  int database_size = 0;
  int true_matches = 0;
  bool scored = false;           // false: no true match in the database (skipped)
  double first_true_rank = NAN;  // expected rank of the first true match (scored only)
  double reciprocal_rank = NAN;  // expected reciprocal rank (scored only)
  double recall_at_1 = NAN;      // P(first true match in the top 1, 5, 10) (scored only)
  double recall_at_5 = NAN;
  double recall_at_10 = NAN;
  int top1_frame = -1;  // first in database order among the top-scoring items
  double top1_score = NAN;
  double top1_distance_m = NAN;        // base distance between query and top1_frame
  bool top1_is_true_match = false;     // of top1_frame
  int top1_tie_size = 0;               // database items sharing the top score
  double top1_expected_correct = NAN;  // true matches among them / top1_tie_size
};

// One point of the top-1 precision-recall curve: queries whose top-1 score >= threshold claim a
// loop; a claim counts as correct with its expected correctness (top1_expected_correct).
struct PrPoint {
  double threshold = 0;
  double precision = 0;
  double recall = 0;  // correct claims / scored queries
};

struct LapMetrics {
  double mrr = NAN;
  int queries_scored = 0;
};

struct MethodMetrics {
  int queries_total = 0;
  int queries_scored = 0;   // queries with at least one true match
  int queries_skipped = 0;  // queries without any: not in any rate below
  double mrr = NAN;         // mean expected reciprocal rank (paper's headline metric)
  double recall_at_1 = NAN;
  double recall_at_5 = NAN;
  double recall_at_10 = NAN;
  std::vector<PrPoint> pr_curve;  // thresholds descending, over scored queries
  double pr_auc = NAN;            // step integration: sum of precision x recall increment (AP)
  double recall_at_100p = NAN;    // largest recall at a threshold with precision 1 (0 if none)
  std::map<int, LapMetrics> per_lap;
  // Timing, filled by SetTiming from per-query measurements, in milliseconds.
  double ms_per_query = NAN;  // mean of extract + match
  double ms_per_query_median = NAN;
  double extract_ms_mean = NAN, extract_ms_median = NAN;
  double match_ms_mean = NAN, match_ms_median = NAN;
  std::vector<QueryRecord> queries;

  // extract_ms and match_ms have one entry per query.
  void SetTiming(const std::vector<double>& extract_ms, const std::vector<double>& match_ms);
  // Every number except the per-query records (those go to queries.csv); NaN becomes null.
  nlohmann::json ToJson() const;
};

// The metrics of a set of per-query records (in query order): every rate, the per-lap MRR and the
// PR curve; no timing. ComputeMetrics ends with it; the bootstrap (bootstrap.h) calls it on
// resampled queries.
MethodMetrics SummariseQueries(std::vector<QueryRecord> records);

// scores[i] is parallel to queries[i].database. poses are indexed by frame number.
MethodMetrics ComputeMetrics(const std::vector<Query>& queries, const std::vector<std::vector<double>>& scores,
                             const std::vector<PoseRecord>& poses);

// The record of a query ranked over a shortlist of its database (the online bench, online.h):
// `shortlisted.database` holds the shortlisted frames (ascending) with their labels, `scores` is
// parallel to it. The database's other database_size - shortlisted.database.size() frames, holding
// the true_matches the shortlist missed, are unranked: they tie below every shortlisted frame, and
// their expected rank counts as metrics.h does for any tie. With the whole database shortlisted it
// is ComputeMetrics' record.
QueryRecord ShortlistRecord(const Query& shortlisted, const std::vector<double>& scores, int database_size,
                            int true_matches, const std::vector<PoseRecord>& poses);

// queries.csv: header then one row per query; empty fields for values a skipped query lacks.
std::string QueryRecordsToCsv(const std::vector<QueryRecord>& records);

}  // namespace hoilcd
