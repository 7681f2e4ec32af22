#include "hoilcd/core/place_recognition/retrieval_index.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <string>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/parallel.h"

namespace hoilcd {
namespace {

// Pairs are scored in tiles of this many queries x references, reference-major within a tile:
// a reference's grid and candidate lattice (~15 KB for 200 points) are read from memory once
// and reused from cache by the tile's queries, whose structures stay cached across the tile.
constexpr int64_t kTileQueries = 32;
constexpr int64_t kTileReferences = 32;

}  // namespace

void RetrievalIndex::Add(const std::vector<Point2>& points) { AddAll({points}, 1); }

void RetrievalIndex::AddAll(const std::vector<std::vector<Point2>>& frames, int threads) {
  const size_t first = grids_.size();
  grids_.resize(first + frames.size());
  ParallelFor(static_cast<int64_t>(frames.size()), threads,
              [&](int64_t i) { grids_[first + i] = PointGrid(frames[i].data(), static_cast<int>(frames[i].size())); });
  for (const std::vector<Point2>& points : frames) {
    points_.insert(points_.end(), points.begin(), points.end());
    offsets_.push_back(static_cast<int64_t>(points_.size()));
  }
}

const Point2* RetrievalIndex::points(int frame, int* count) const {
  HOILCD_CHECK_MSG(frame >= 0 && frame < size(), "frame " << frame << " not in [0, " << size() << ")");
  HOILCD_CHECK(count != nullptr);
  *count = static_cast<int>(offsets_[frame + 1] - offsets_[frame]);
  return points_.data() + offsets_[frame];
}

std::vector<std::vector<float>> RetrievalIndex::ScoreAll(const std::vector<int>& queries,
                                                         const std::vector<int>& database,
                                                         const MatchOptions& match_options,
                                                         const RansacOptions& ransac_options, uint64_t seed,
                                                         int threads) const {
  const std::string match_problem = match_options.Check();
  HOILCD_CHECK_MSG(match_problem.empty(), match_problem);
  const std::string ransac_problem = ransac_options.Check();
  HOILCD_CHECK_MSG(ransac_problem.empty(), ransac_problem);
  for (const std::vector<int>* ids : {&queries, &database}) {
    for (int id : *ids) {
      HOILCD_CHECK_MSG(id >= 0 && id < size(), "frame " << id << " not in [0, " << size() << ")");
    }
  }
  const int64_t num_database = static_cast<int64_t>(database.size());
  std::vector<std::vector<float>> scores(queries.size(), std::vector<float>(database.size(), 0.0f));
  const int num_threads = ResolveThreadCount(threads);
  std::vector<PairScorer> scorers(num_threads);
  const int64_t num_queries = static_cast<int64_t>(queries.size());
  const int64_t query_tiles = (num_queries + kTileQueries - 1) / kTileQueries;
  const int64_t reference_tiles = (num_database + kTileReferences - 1) / kTileReferences;
  ParallelForChunks(query_tiles * reference_tiles, 1, num_threads, [&](int64_t begin, int64_t end, int worker) {
    PairScorer& scorer = scorers[worker];
    for (int64_t tile = begin; tile < end; ++tile) {
      const int64_t q0 = (tile / reference_tiles) * kTileQueries;
      const int64_t d0 = (tile % reference_tiles) * kTileReferences;
      const int64_t q1 = std::min(num_queries, q0 + kTileQueries);
      const int64_t d1 = std::min(num_database, d0 + kTileReferences);
      for (int64_t di = d0; di < d1; ++di) {
        const int r = database[di];
        for (int64_t qi = q0; qi < q1; ++qi) {
          const int q = queries[qi];
          scores[qi][di] =
              static_cast<float>(scorer.Score(points_.data() + offsets_[q], grids_[q], points_.data() + offsets_[r],
                                              grids_[r], match_options, ransac_options, PairSeed(seed, q, r)));
        }
      }
    }
  });
  return scores;
}

std::vector<std::vector<float>> RetrievalIndex::ScoreDatabases(const std::vector<int>& queries,
                                                               const std::vector<std::vector<int>>& databases,
                                                               const MatchOptions& match_options,
                                                               const RansacOptions& ransac_options, uint64_t seed,
                                                               int threads, std::vector<int64_t>* time_ns,
                                                               ProgressReporter* progress) const {
  std::vector<std::vector<int64_t>> variant_ns;
  std::vector<std::vector<std::vector<float>>> scores =
      ScoreDatabases(queries, databases, match_options, std::vector<RansacOptions>{ransac_options}, seed, threads,
                     time_ns != nullptr ? &variant_ns : nullptr, progress);
  if (time_ns != nullptr) *time_ns = std::move(variant_ns.front());
  return std::move(scores.front());
}

std::vector<std::vector<std::vector<float>>> RetrievalIndex::ScoreDatabases(
    const std::vector<int>& queries, const std::vector<std::vector<int>>& databases, const MatchOptions& match_options,
    const std::vector<RansacOptions>& variants, uint64_t seed, int threads, std::vector<std::vector<int64_t>>* time_ns,
    ProgressReporter* progress) const {
  const std::string match_problem = match_options.Check();
  HOILCD_CHECK_MSG(match_problem.empty(), match_problem);
  HOILCD_CHECK_MSG(!variants.empty(), "no RANSAC variant to score under");
  for (const RansacOptions& ransac : variants) {
    const std::string ransac_problem = ransac.Check();
    HOILCD_CHECK_MSG(ransac_problem.empty(), ransac_problem);
  }
  HOILCD_CHECK_MSG(databases.size() == queries.size(), databases.size()
                                                           << " databases for " << queries.size() << " queries");
  for (size_t i = 0; i < queries.size(); ++i) {
    HOILCD_CHECK_MSG(queries[i] >= 0 && queries[i] < size(), "frame " << queries[i] << " not in [0, " << size() << ")");
    for (size_t j = 0; j < databases[i].size(); ++j) {
      const int r = databases[i][j];
      HOILCD_CHECK_MSG(r >= 0 && r < size(), "frame " << r << " not in [0, " << size() << ")");
      HOILCD_CHECK_MSG(j == 0 || databases[i][j - 1] < r, "database " << i << " is not ascending");
    }
  }
  const int count = static_cast<int>(variants.size());
  std::vector<std::vector<std::vector<float>>> scores(count, std::vector<std::vector<float>>(queries.size()));
  for (int v = 0; v < count; ++v) {
    for (size_t i = 0; i < queries.size(); ++i) scores[v][i].assign(databases[i].size(), 0.0f);
  }
  // spent_ns[i * count + v]: query i's time under variant v.
  std::vector<std::atomic<int64_t>> spent_ns(queries.size() * count);
  const int num_threads = ResolveThreadCount(threads);
  std::vector<PairScorer> scorers(num_threads);
  // Tiles: kTileQueries consecutive queries x kTileReferences consecutive frame ids; each query
  // scores the part of its database inside the tile's frame range.
  const int64_t num_queries = static_cast<int64_t>(queries.size());
  const int64_t query_tiles = (num_queries + kTileQueries - 1) / kTileQueries;
  const int64_t frame_tiles = (size() + kTileReferences - 1) / kTileReferences;
  ParallelForChunks(query_tiles * frame_tiles, 1, num_threads, [&](int64_t begin, int64_t end, int worker) {
    PairScorer& scorer = scorers[worker];
    std::vector<int> inliers(count);
    std::vector<int64_t> pair_alone_ns(count), alone_ns(count);
    for (int64_t tile = begin; tile < end; ++tile) {
      const int64_t q0 = (tile / frame_tiles) * kTileQueries;
      const int r0 = static_cast<int>((tile % frame_tiles) * kTileReferences);
      const int r1 = static_cast<int>(std::min<int64_t>(size(), r0 + kTileReferences));
      for (int64_t qi = q0; qi < std::min(num_queries, q0 + kTileQueries); ++qi) {
        const std::vector<int>& database = databases[qi];
        const auto first = std::lower_bound(database.begin(), database.end(), r0);
        const auto last = std::lower_bound(first, database.end(), r1);
        if (first == last) continue;
        // The row is timed whole; with several variants their RANSAC is timed too, and a variant is
        // charged the row less the RANSAC time plus what its own RANSAC costs alone (drawing the
        // samples, which the variants share, and its own scoring): the matching and its RANSAC.
        const auto start = std::chrono::steady_clock::now();
        std::fill(alone_ns.begin(), alone_ns.end(), 0);
        int64_t ransac_ns = 0;
        const int q = queries[qi];
        for (auto it = first; it != last; ++it) {
          const int r = *it;
          int64_t pair_ransac_ns = 0;
          scorer.ScoreVariants(points_.data() + offsets_[q], grids_[q], points_.data() + offsets_[r], grids_[r],
                               match_options, variants.data(), count, PairSeed(seed, q, r), inliers.data(),
                               count > 1 ? pair_alone_ns.data() : nullptr, count > 1 ? &pair_ransac_ns : nullptr);
          ransac_ns += pair_ransac_ns;
          for (int v = 0; v < count; ++v) {
            scores[v][qi][it - database.begin()] = static_cast<float>(inliers[v]);
            if (count > 1) alone_ns[v] += pair_alone_ns[v];
          }
        }
        const int64_t row_ns =
            std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start).count();
        for (int v = 0; v < count; ++v) spent_ns[qi * count + v] += row_ns - ransac_ns + alone_ns[v];
        if (progress != nullptr) progress->Update(last - first);
      }
    }
  });
  if (time_ns != nullptr) {
    time_ns->assign(count, std::vector<int64_t>(queries.size()));
    for (size_t i = 0; i < queries.size(); ++i) {
      for (int v = 0; v < count; ++v) (*time_ns)[v][i] = spent_ns[i * count + v];
    }
  }
  return scores;
}

}  // namespace hoilcd
