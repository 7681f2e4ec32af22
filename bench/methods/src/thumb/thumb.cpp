// Global baseline: patch-normalised thumbnails compared by normalised cross-correlation.
#include <algorithm>
#include <chrono>
#include <numeric>

#include "hoilcd/bench/methods/bench_options.h"
#include "hoilcd/bench/methods/loop_closure_method.h"

namespace hoilcd {
namespace {

class Thumb : public LoopClosureMethod {
 public:
  std::string Name() const override { return "thumb"; }
  std::string Description() const override {
    return "global baseline: patch-normalised thumbnail correlation (SeqSLAM-style)";
  }
  std::set<FrontEnd> FrontEnds() const override { return {FrontEnd::kThumbnails}; }
  MethodScores Score(const MethodContext& c) const override {
    using Clock = std::chrono::steady_clock;
    const int n = c.dataset.num_frames();
    const auto t = Clock::now();
    std::vector<int> all(n);
    std::iota(all.begin(), all.end(), 0);
    MethodScores out;
    // The dense frame x frame matrix: thumb-seq's sequence search runs over it.
    out.dense = c.front_ends.thumbnails.ScoreAll(all, all, c.threads);
    const double per_query_ms = std::chrono::duration<double, std::milli>(Clock::now() - t).count() / std::max(1, n);
    for (const Query& q : c.queries()) {
      out.scores.emplace_back();
      for (int r : q.database) out.scores.back().push_back(out.dense[q.frame][r]);
    }
    out.match_ms.assign(c.queries().size(), per_query_ms);
    out.extract_ms = c.PerQuery(c.front_ends.thumbnails_ms);
    return out;
  }
};

}  // namespace

std::unique_ptr<LoopClosureMethod> MakeThumbMethod() { return std::make_unique<Thumb>(); }

}  // namespace hoilcd
