// Track-aware DLCD: people are paired between the two frames first, then correspondences are
// drawn between the HOI contours of paired people only.
#include <chrono>

#include "hoilcd/bench/loop_closure_method.h"
#include "hoilcd/bench/runner.h"
#include "hoilcd/core/parallel.h"
#include "hoilcd/core/progress.h"
#include "hoilcd/core/track_aware_matching.h"

namespace hoilcd {
namespace {

class DlcdTrack : public LoopClosureMethod {
 public:
  std::string Name() const override { return "dlcd-track"; }
  std::string Description() const override {
    return "track-aware DLCD: correspondences between the HOI contours of paired people";
  }
  ShownFeatures Features() const override { return ShownFeatures::kHoiPoints; }
  std::set<FrontEnd> FrontEnds() const override { return {FrontEnd::kPersons}; }
  MethodScores Score(const MethodContext& c) const override {
    using Clock = std::chrono::steady_clock;
    const std::vector<Query>& queries = c.queries();
    const auto& hoi = c.front_ends.hoi;
    MethodScores out;
    out.scores.resize(queries.size());
    out.match_ms.assign(queries.size(), 0.0);
    ProgressReporter progress(Name(), static_cast<int64_t>(queries.size()), "queries");
    for (size_t i = 0; i < queries.size(); ++i) {
      const Query& q = queries[i];
      const auto t = Clock::now();
      out.scores[i].assign(q.database.size(), 0.0);
      if (c.labelling.to_score[i]) {
        ParallelFor(static_cast<int64_t>(q.database.size()), c.threads, [&](int64_t j) {
          const int r = q.database[j];
          out.scores[i][j] = ScoreTrackAwarePair(hoi[q.frame], hoi[r], c.options.track_aware, c.options.ransac,
                                                 c.seed, q.frame, r);
        });
      }
      out.match_ms[i] = std::chrono::duration<double, std::milli>(Clock::now() - t).count();
      progress.Update();
    }
    progress.Done();
    out.extract_ms = c.PerQuery(c.front_ends.persons_ms);
    return out;
  }
};

}  // namespace

std::unique_ptr<LoopClosureMethod> MakeDlcdTrackMethod() { return std::make_unique<DlcdTrack>(); }

}  // namespace hoilcd
