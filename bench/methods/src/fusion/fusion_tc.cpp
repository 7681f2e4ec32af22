// Fusion with temporal consistency: a query's candidates must agree with its neighbours' in time.
#include <algorithm>
#include <chrono>
#include <set>

#include "hoilcd/bench/methods/loop_closure_method.h"
#include "hoilcd/core/place_recognition/temporal_consistency.h"

namespace hoilcd {
namespace {

// Temporal consistency over per-query databases: scores go into the union of all databases
// (frames absent from a query's own database score below everything), then back.
std::vector<std::vector<double>> TemporalConsistencyOfQueries(const std::vector<Query>& queries,
                                                              const std::vector<std::vector<double>>& scores,
                                                              const TemporalConsistencyOptions& options) {
  std::set<int> union_frames;
  double lowest = 0;
  for (size_t i = 0; i < queries.size(); ++i) {
    union_frames.insert(queries[i].database.begin(), queries[i].database.end());
    for (double v : scores[i]) lowest = std::min(lowest, v);
  }
  const std::vector<int> database(union_frames.begin(), union_frames.end());
  std::vector<int> column(database.empty() ? 0 : database.back() + 1, -1);
  for (size_t j = 0; j < database.size(); ++j) column[database[j]] = static_cast<int>(j);
  std::vector<int> query_frames;
  std::vector<std::vector<float>> table(queries.size(),
                                        std::vector<float>(database.size(), static_cast<float>(lowest - 1)));
  for (size_t i = 0; i < queries.size(); ++i) {
    query_frames.push_back(queries[i].frame);
    for (size_t j = 0; j < queries[i].database.size(); ++j) {
      table[i][column[queries[i].database[j]]] = static_cast<float>(scores[i][j]);
    }
  }
  const auto gated = TemporalConsistencyScores(query_frames, database, table, options);
  std::vector<std::vector<double>> out(queries.size());
  for (size_t i = 0; i < queries.size(); ++i) {
    for (int r : queries[i].database) out[i].push_back(gated[i][column[r]]);
  }
  return out;
}

class FusionTc : public LoopClosureMethod {
 public:
  std::string Name() const override { return "fusion-tc"; }
  std::string Description() const override {
    return "fusion with temporal consistency (consecutive queries must agree)";
  }
  std::vector<std::string> Inputs() const override { return {"fusion"}; }
  std::unique_ptr<MethodOptions> Options() const override {
    static const OptionTable<TemporalConsistencyOptions> table =
        TemporalConsistencyOptions::Table().Only({"consecutive_queries", "candidates_per_query", "max_frame_gap"});
    return std::make_unique<OptionsOf<TemporalConsistencyOptions>>(table);
  }
  MethodScores Score(const MethodContext& c) const override {
    using Clock = std::chrono::steady_clock;
    const MethodScores& fusion = c.Input("fusion");
    const auto t = Clock::now();
    MethodScores out;
    out.scores = TemporalConsistencyOfQueries(c.queries(), fusion.scores, c.Own<TemporalConsistencyOptions>());
    const double per_query = std::chrono::duration<double, std::milli>(Clock::now() - t).count() /
                             static_cast<double>(std::max<size_t>(1, c.queries().size()));
    out.extract_ms = fusion.extract_ms;
    out.match_ms = fusion.match_ms;
    for (double& m : out.match_ms) m += per_query;
    return out;
  }
};

}  // namespace

std::unique_ptr<LoopClosureMethod> MakeFusionTcMethod() { return std::make_unique<FusionTc>(); }

}  // namespace hoilcd
