#include "point_set_scoring.h"

#include <chrono>

#include "hoilcd/bench/runner.h"
#include "hoilcd/core/progress.h"

namespace hoilcd {

MethodScores ScorePointSets(const MethodContext& context, const std::string& title, const RetrievalIndex& index,
                            const RansacOptions& ransac, const std::vector<double>& extract_ms_per_frame) {
  using Clock = std::chrono::steady_clock;
  const std::vector<Query>& queries = context.queries();
  MethodScores out;
  out.scores.resize(queries.size());
  out.match_ms.assign(queries.size(), 0.0);
  ProgressReporter progress(title, static_cast<int64_t>(queries.size()), "queries");
  for (size_t i = 0; i < queries.size(); ++i) {
    const Query& q = queries[i];
    const auto start = Clock::now();
    if (context.labelling.to_score[i] && !q.database.empty()) {
      const auto row = index.ScoreAll({q.frame}, q.database, context.options.match, ransac, context.seed, context.threads);
      out.scores[i].assign(row[0].begin(), row[0].end());
    } else {
      out.scores[i].assign(q.database.size(), 0.0);  // skipped queries are not scored
    }
    out.match_ms[i] = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    progress.Update();
  }
  progress.Done();
  out.extract_ms = context.PerQuery(extract_ms_per_frame);
  return out;
}

RansacOptions LocallyOptimised(const BenchOptions& options) {
  RansacOptions lo = options.ransac;
  lo.local_optimisation_refits = options.lo_refits;
  return lo;
}

}  // namespace hoilcd
