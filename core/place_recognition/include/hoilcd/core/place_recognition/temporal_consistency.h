// Temporal consistency of loop candidates, as DBoW2 / ORB-SLAM accept a loop only when k
// consecutive queries agree: a candidate is kept on top when the previous k-1 queries matched a
// forward-moving chain of database frames leading to it. A pure function over score tables.
#pragma once

#include <string>
#include <vector>

#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

// Defaults and ranges: Table() in temporal_consistency.cpp.
struct TemporalConsistencyOptions {
  int consecutive_queries;   // k: queries in a consistent run, current one included (1 = off)
  int candidates_per_query;  // K: each earlier query supports the chain with its K best frames
  int max_frame_gap;         // frames a chain may advance in the database per query step
  int max_query_gap;         // frames between two queries for them to count as consecutive

  TemporalConsistencyOptions();  // the registered defaults
  // Every field once: name, default, unit, range, description.
  static const OptionTable<TemporalConsistencyOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

// `query_frames` (ascending, the rows of `scores`) and `database_frames` (ascending, the columns)
// are frame numbers; scores[q][j] is any similarity, higher = better (inlier counts, RRF, NCC).
//
// Candidate j of query q is supported when there is a chain q-k+1, ..., q-1, q of consecutive
// queries (each at most max_query_gap frames after the one before) whose matches d_{q-k+1} <= ...
// <= d_{q-1} <= database_frames[j] advance by at most max_frame_gap frames per step, every
// earlier d being among its own query's K best database frames (ties to the lower column).
//
// Output, same shape: supported candidates keep their score; unsupported ones are moved below
// every supported one by subtracting the table's span (max - min + 1), keeping their order.
// So each query's ranking is lexicographic (supported first, then by score), which keeps MRR
// meaningful (a rejected true match still has a rank), while a threshold on the top-1 score for
// precision-recall accepts unsupported loops only after every supported one, i.e. gates them
// as DBoW2 does. k = 1 returns the scores unchanged.
std::vector<std::vector<float>> TemporalConsistencyScores(const std::vector<int>& query_frames,
                                                          const std::vector<int>& database_frames,
                                                          const std::vector<std::vector<float>>& scores,
                                                          const TemporalConsistencyOptions& options);

}  // namespace hoilcd
