#include "hoilcd/core/place_recognition/rank_fusion.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "hoilcd/core/util/error.h"

namespace hoilcd {

std::vector<double> ReciprocalRankFusion(const std::vector<std::vector<int>>& rankings, int num_database, double k) {
  HOILCD_CHECK_MSG(num_database >= 0, "num_database must be >= 0, got " << num_database);
  HOILCD_CHECK_MSG(std::isfinite(k) && k > -1.0, "RRF constant k must be > -1, got " << k);
  std::vector<double> scores(num_database, 0.0);
  std::vector<int> seen_in(num_database, -1);
  for (size_t list = 0; list < rankings.size(); ++list) {
    const std::vector<int>& ranking = rankings[list];
    for (size_t position = 0; position < ranking.size(); ++position) {
      const int item = ranking[position];
      HOILCD_CHECK_MSG(item >= 0 && item < num_database,
                       "ranking " << list << " holds index " << item << " outside [0, " << num_database << ")");
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
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return scores[a] > scores[b]; });
  return order;
}

std::vector<double> FractionalRanks(const std::vector<double>& scores) {
  const std::vector<int> order = RankByScore(scores);
  std::vector<double> ranks(scores.size());
  for (size_t begin = 0; begin < order.size();) {
    size_t end = begin + 1;
    while (end < order.size() && scores[order[end]] == scores[order[begin]]) ++end;
    const double mean_rank = 0.5 * static_cast<double>(begin + 1 + end);  // positions begin+1..end
    for (size_t i = begin; i < end; ++i) ranks[order[i]] = mean_rank;
    begin = end;
  }
  return ranks;
}

std::vector<double> ReciprocalRankFusionOfScores(const std::vector<std::vector<double>>& scores, double k) {
  HOILCD_CHECK_MSG(std::isfinite(k) && k > -1.0, "RRF constant k must be > -1, got " << k);
  if (scores.empty()) return {};
  std::vector<double> fused(scores.front().size(), 0.0);
  for (const std::vector<double>& list : scores) {
    HOILCD_CHECK_MSG(list.size() == fused.size(), "score lists differ in size");
    const std::vector<double> ranks = FractionalRanks(list);
    for (size_t i = 0; i < fused.size(); ++i) fused[i] += 1.0 / (k + ranks[i]);
  }
  return fused;
}

}  // namespace hoilcd
