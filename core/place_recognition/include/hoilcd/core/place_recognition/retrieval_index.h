// Retrieval index for loop closure: per-frame 2-D point sets kept compactly (one flat array plus
// offsets, with a prebuilt nearest-neighbour grid per frame) and all-pairs scoring
// (MNN -> vertical filter -> RANSAC inlier count) in parallel over threads.
#pragma once

#include <cstdint>
#include <vector>

#include "hoilcd/core/matching/matching.h"
#include "hoilcd/core/util/progress.h"

namespace hoilcd {

class RetrievalIndex {
 public:
  // Frame ids are 0..size-1 in Add order. Coordinates must be finite.
  void Add(const std::vector<Point2>& points);
  // Adds frames in order, building their grids in parallel (threads 0 = all cores): the same
  // index as adding them one by one.
  void AddAll(const std::vector<std::vector<Point2>>& frames, int threads);
  int size() const { return static_cast<int>(grids_.size()); }
  // The points of `frame`; *count receives how many.
  const Point2* points(int frame, int* count) const;

  // scores[i][j] = ScorePair(frame queries[i], frame database[j], ..., seed, queries[i],
  // database[j]) for all pairs; parallel (threads 0 = all cores), identical at any thread count.
  std::vector<std::vector<float>> ScoreAll(const std::vector<int>& queries, const std::vector<int>& database,
                                           const MatchOptions& match_options, const RansacOptions& ransac_options,
                                           uint64_t seed, int threads) const;

  // Each query against its own database: scores[i][j] = the ScoreAll score of frame queries[i]
  // and frame databases[i][j]. databases[i] must be ascending. All pairs of all queries are
  // one parallel loop over tiles of consecutive queries x frame ranges, so both threads stay
  // busy however small one database is; identical at any thread count. When time_ns is given,
  // (*time_ns)[i] gets the time spent on query i's pairs (summed over threads); progress, when
  // given, is advanced by every pair scored.
  std::vector<std::vector<float>> ScoreDatabases(const std::vector<int>& queries,
                                                 const std::vector<std::vector<int>>& databases,
                                                 const MatchOptions& match_options, const RansacOptions& ransac_options,
                                                 uint64_t seed, int threads, std::vector<int64_t>* time_ns = nullptr,
                                                 ProgressReporter* progress = nullptr) const;
  // The same under each of several RANSAC variants in one pass, each pair's MNN and vertical
  // filter found once for all, and the RANSAC samples drawn once for the variants that share
  // them (RansacCounter): result[v] is ScoreDatabases(..., variants[v], ...). When time_ns is
  // given, (*time_ns)[v][i] is what query i's pairs take under variant v alone (the matching plus
  // its RANSAC, summed over threads).
  std::vector<std::vector<std::vector<float>>> ScoreDatabases(
      const std::vector<int>& queries, const std::vector<std::vector<int>>& databases,
      const MatchOptions& match_options, const std::vector<RansacOptions>& variants, uint64_t seed, int threads,
      std::vector<std::vector<int64_t>>* time_ns = nullptr, ProgressReporter* progress = nullptr) const;

 private:
  std::vector<Point2> points_;          // every frame's points, frame after frame
  std::vector<int64_t> offsets_ = {0};  // frame f holds points_[offsets_[f], offsets_[f+1])
  std::vector<PointGrid> grids_;        // nearest-neighbour grid per frame
};

}  // namespace hoilcd
