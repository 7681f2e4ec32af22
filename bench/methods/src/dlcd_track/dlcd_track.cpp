// Track-aware DLCD: people are paired between the two frames first, then correspondences are
// drawn between the HOI contours of paired people only.
#include <algorithm>
#include <atomic>
#include <chrono>

#include "hoilcd/bench/methods/loop_closure_method.h"
#include "hoilcd/bench/methods/method_params.h"
#include "hoilcd/core/matching/track_aware_matching.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/core/util/progress.h"

namespace hoilcd {
namespace {

// dlcd-track's own options (--param dlcd-track.max_pair_cost=..., dlcd-track.ransac_trials=...).
struct DlcdTrackOptions {
  RansacOptions ransac;
  TrackAwareOptions track_aware;

  static const OptionTable<DlcdTrackOptions>& Table() {
    using O = DlcdTrackOptions;
    static const OptionTable<O> table =
        OptionTable<O>()
            .Flatten(&O::ransac, RansacParams())
            .Flatten(&O::track_aware, TrackAwareOptions::Table().Only({"min_points_per_person", "max_pair_cost"}));
    return table;
  }
};

class DlcdTrack : public LoopClosureMethod {
 public:
  std::string Name() const override { return "dlcd-track"; }
  std::string Description() const override {
    return "track-aware DLCD: correspondences between the HOI contours of paired people";
  }
  ShownFeatures Features() const override { return ShownFeatures::kHoiPoints; }
  std::set<FrontEnd> FrontEnds() const override { return {FrontEnd::kPersons}; }
  std::unique_ptr<MethodOptions> Options() const override {
    return std::make_unique<OptionsOf<DlcdTrackOptions>>(DlcdTrackOptions::Table());
  }
  MethodScores Score(const MethodContext& c) const override {
    using Clock = std::chrono::steady_clock;
    const std::vector<Query>& queries = c.queries();
    const auto& hoi = c.front_ends.hoi;
    const DlcdTrackOptions& own = c.Own<DlcdTrackOptions>();
    MethodScores out;
    out.scores.resize(queries.size());
    out.match_ms.assign(queries.size(), 0.0);
    // Every pair of every scored query in one parallel loop (chunks of kChunkPairs pairs of
    // one query), so both threads stay busy; each query's time is summed over its chunks.
    constexpr int64_t kChunkPairs = 64;
    struct Chunk {
      size_t query;
      int64_t begin, end;
    };
    std::vector<Chunk> chunks;
    int64_t pairs = 0;
    for (size_t i = 0; i < queries.size(); ++i) {
      const int64_t size = static_cast<int64_t>(queries[i].database.size());
      out.scores[i].assign(size, 0.0);
      if (!c.labelling.to_score[i]) continue;
      for (int64_t b = 0; b < size; b += kChunkPairs) chunks.push_back({i, b, std::min(size, b + kChunkPairs)});
      pairs += size;
    }
    // Each frame's persons grouped once, counted in its extraction time like the front ends'.
    std::vector<TrackAwareFrame> frames(hoi.size());
    std::vector<int64_t> prepare_ns(hoi.size());
    ParallelFor(static_cast<int64_t>(hoi.size()), c.threads, [&](int64_t f) {
      const auto t = Clock::now();
      frames[f] = PrepareTrackAwareFrame(hoi[f], own.track_aware);
      prepare_ns[f] = std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - t).count();
    });
    std::vector<std::atomic<int64_t>> spent_ns(queries.size());
    ProgressReporter progress(Name(), pairs, "pairs");
    ParallelFor(static_cast<int64_t>(chunks.size()), c.threads, [&](int64_t k) {
      const Chunk& chunk = chunks[k];
      const Query& q = queries[chunk.query];
      const auto t = Clock::now();
      for (int64_t j = chunk.begin; j < chunk.end; ++j) {
        const int r = q.database[j];
        out.scores[chunk.query][j] =
            ScoreTrackAwarePair(frames[q.frame], frames[r], own.track_aware, own.ransac, c.seed, q.frame, r);
      }
      spent_ns[chunk.query] += std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - t).count();
      progress.Update(chunk.end - chunk.begin);
    });
    progress.Done();
    for (size_t i = 0; i < queries.size(); ++i) out.match_ms[i] = 1e-6 * static_cast<double>(spent_ns[i]);
    std::vector<double> extract_ms = c.front_ends.persons_ms;  // the persons' front end, then grouping
    for (size_t f = 0; f < extract_ms.size(); ++f) extract_ms[f] += 1e-6 * static_cast<double>(prepare_ns[f]);
    out.extract_ms = c.PerQuery(extract_ms);
    return out;
  }
  // The pair's contour correspondences and RANSAC as Score runs them (same options and stream),
  // on the HOI points with their track ids.
  std::optional<PairMatches> MatchPair(const PairMatchInput& input) const override {
    const DlcdTrackOptions& own = OptionsValue<DlcdTrackOptions>(input.own);
    return MatchTrackAwarePair(PrepareTrackAwareFrame(input.query_hoi, own.track_aware),
                               PrepareTrackAwareFrame(input.reference_hoi, own.track_aware), own.track_aware,
                               own.ransac, input.seed, input.query_frame, input.reference_frame);
  }
};

}  // namespace

std::unique_ptr<LoopClosureMethod> MakeDlcdTrackMethod() { return std::make_unique<DlcdTrack>(); }

}  // namespace hoilcd
