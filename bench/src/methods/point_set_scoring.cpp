#include "point_set_scoring.h"

#include "hoilcd/bench/method_params.h"
#include "hoilcd/bench/runner.h"
#include "hoilcd/core/progress.h"

namespace hoilcd {

MethodScores ScorePointSets(const MethodContext& context, const std::string& title, const RetrievalIndex& index,
                            const RansacOptions& ransac, const std::vector<double>& extract_ms_per_frame) {
  const std::vector<Query>& queries = context.queries();
  MethodScores out;
  out.scores.resize(queries.size());
  out.match_ms.assign(queries.size(), 0.0);
  // Every scored query in one parallel call; skipped queries are not scored (all 0).
  std::vector<size_t> scored;
  std::vector<int> frames;
  std::vector<std::vector<int>> databases;
  for (size_t i = 0; i < queries.size(); ++i) {
    out.scores[i].assign(queries[i].database.size(), 0.0);
    if (!context.labelling.to_score[i] || queries[i].database.empty()) continue;
    scored.push_back(i);
    frames.push_back(queries[i].frame);
    databases.push_back(queries[i].database);
  }
  int64_t pairs = 0;
  for (const std::vector<int>& d : databases) pairs += static_cast<int64_t>(d.size());
  ProgressReporter progress(title, pairs, "pairs");
  std::vector<int64_t> time_ns;
  const auto rows = index.ScoreDatabases(frames, databases, context.options.match, ransac, context.seed,
                                         context.threads, &time_ns, &progress);
  for (size_t k = 0; k < scored.size(); ++k) {
    out.scores[scored[k]].assign(rows[k].begin(), rows[k].end());
    out.match_ms[scored[k]] = 1e-6 * static_cast<double>(time_ns[k]);
  }
  progress.Done();
  out.extract_ms = context.PerQuery(extract_ms_per_frame);
  return out;
}

const OptionTable<BenchOptions>& PointSetParams(bool lo) {
  static const OptionTable<BenchOptions> plain =
      OptionTable<BenchOptions>().Flatten(&BenchOptions::ransac, RansacParams()).Flatten(&BenchOptions::match, MatchParams());
  static const OptionTable<BenchOptions> with_lo = OptionTable<BenchOptions>(plain).Add(
      "lo_refits", &BenchOptions::lo_refits, 2, "", OptionRange::Any().AtLeast(1),
      "least-squares refits of the homography on its inliers");
  return lo ? with_lo : plain;
}

RansacOptions LocallyOptimised(const BenchOptions& options) {
  RansacOptions lo = options.ransac;
  lo.local_optimisation_refits = options.lo_refits;
  return lo;
}

}  // namespace hoilcd
