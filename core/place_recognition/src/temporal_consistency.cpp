#include "hoilcd/core/place_recognition/temporal_consistency.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/sizes.h"

namespace hoilcd {
namespace {

// Columns of the K best scores of one row, ties to the lower column.
std::vector<int> TopColumns(const std::vector<float>& row, int k) {
  std::vector<int> columns(row.size());
  std::iota(columns.begin(), columns.end(), 0);
  const size_t keep = std::min(columns.size(), static_cast<size_t>(k));
  std::partial_sort(columns.begin(), columns.begin() + static_cast<std::ptrdiff_t>(keep), columns.end(),
                    [&](int a, int b) {
                      const float sa = row[static_cast<size_t>(a)];
                      const float sb = row[static_cast<size_t>(b)];
                      return sa > sb || (sa == sb && a < b);
                    });
  columns.resize(keep);
  return columns;
}

bool StrictlyAscending(const std::vector<int>& frames) {
  return std::adjacent_find(frames.begin(), frames.end(), [](int a, int b) { return a >= b; }) == frames.end();
}

}  // namespace

TemporalConsistencyOptions::TemporalConsistencyOptions() { Table().FillDefaults(this); }

const OptionTable<TemporalConsistencyOptions>& TemporalConsistencyOptions::Table() {
  using O = TemporalConsistencyOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("consecutive_queries", &O::consecutive_queries, 3, "", R::Closed(1, kMaxFrames),
               "queries in a consistent run, the current one included (1 = off)")
          .Add("candidates_per_query", &O::candidates_per_query, 5, "", R::Closed(1, kMaxFrames),
               "best frames of each earlier query that support a chain")
          .Add("max_frame_gap", &O::max_frame_gap, 10, "frames", R::Closed(0, kMaxFrames),
               "database frames a chain may advance per query step")
          .Add("max_query_gap", &O::max_query_gap, 1, "frames", R::Closed(1, kMaxFrames),
               "frames between two queries for them to count as consecutive");
  return table;
}

std::string TemporalConsistencyOptions::Check() const { return Table().FirstProblem(*this); }

std::vector<std::vector<float>> TemporalConsistencyScores(const std::vector<int>& query_frames,
                                                          const std::vector<int>& database_frames,
                                                          const std::vector<std::vector<float>>& scores,
                                                          const TemporalConsistencyOptions& options) {
  HOILCD_CHECK_MSG(options.Check().empty(), options.Check());
  HOILCD_CHECK_MSG(scores.size() == query_frames.size(), "one score row per query");
  HOILCD_CHECK_MSG(StrictlyAscending(query_frames), "query frames must be strictly ascending");
  HOILCD_CHECK_MSG(StrictlyAscending(database_frames), "database frames must be strictly ascending");
  float min_score = 0.0f, max_score = 0.0f;
  bool any = false;
  for (const auto& row : scores) {
    HOILCD_CHECK_MSG(row.size() == database_frames.size(), "one score column per database frame");
    for (float s : row) {
      HOILCD_CHECK_MSG(std::isfinite(s), "scores must be finite");
      min_score = any ? std::min(min_score, s) : s;
      max_score = any ? std::max(max_score, s) : s;
      any = true;
    }
  }
  std::vector<std::vector<float>> out = scores;
  const int k = options.consecutive_queries;
  if (k == 1 || !any) return out;
  const float span = max_score - min_score + 1.0f;

  const size_t columns = database_frames.size();
  // run[j]: queries in the longest consistent chain ending at candidate j of the current query,
  // capped at k.
  std::vector<int> previous_run, run;
  for (size_t q = 0; q < scores.size(); ++q) {
    previous_run.swap(run);
    run.assign(columns, 1);
    if (q > 0 && query_frames[q] - query_frames[q - 1] <= options.max_query_gap) {
      for (int p : TopColumns(scores[q - 1], options.candidates_per_query)) {
        const int from = database_frames[static_cast<size_t>(p)];
        const int chain = std::min(k, previous_run[static_cast<size_t>(p)] + 1);
        // Candidates whose frame lies in [from, from + max_frame_gap]: a contiguous column range.
        auto it = std::lower_bound(database_frames.begin(), database_frames.end(), from);
        for (; it != database_frames.end() && *it - from <= options.max_frame_gap; ++it) {
          int& r = run[static_cast<size_t>(it - database_frames.begin())];
          r = std::max(r, chain);
        }
      }
    }
    for (size_t j = 0; j < columns; ++j) {
      if (run[j] < k) out[q][j] -= span;
    }
  }
  return out;
}

}  // namespace hoilcd
