#include "hoilcd/core/rank_fusion.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "hoilcd/core/error.h"

namespace hoilcd {

std::vector<double> ReciprocalRankFusion(const std::vector<std::vector<int>>& rankings,
                                         int num_database, double k) {
  HOILCD_CHECK_MSG(num_database >= 0, "num_database must be >= 0, got " << num_database);
  HOILCD_CHECK_MSG(std::isfinite(k) && k > -1.0, "RRF constant k must be > -1, got " << k);
  std::vector<double> scores(num_database, 0.0);
  std::vector<int> seen_in(num_database, -1);
  for (size_t list = 0; list < rankings.size(); ++list) {
    const std::vector<int>& ranking = rankings[list];
    for (size_t position = 0; position < ranking.size(); ++position) {
      const int item = ranking[position];
      HOILCD_CHECK_MSG(item >= 0 && item < num_database,
                       "ranking " << list << " holds index " << item << " outside [0, "
                                  << num_database << ")");
      HOILCD_CHECK_MSG(seen_in[item] != static_cast<int>(list),
                       "ranking " << list << " lists index " << item << " twice");
      seen_in[item] = static_cast<int>(list);
      scores[item] += 1.0 / (k + static_cast<double>(position + 1));
    }
  }
  return scores;
}

std::vector<int> RankByScore(const std::vector<double>& scores) {
  for (size_t i = 0; i < scores.size(); ++i) {
    HOILCD_CHECK_MSG(!std::isnan(scores[i]), "score " << i << " is NaN");
  }
  std::vector<int> order(scores.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return scores[a] > scores[b]; });
  return order;
}

}  // namespace hoilcd
