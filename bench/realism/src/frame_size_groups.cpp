#include "hoilcd/bench/realism/frame_size_groups.h"

#include <algorithm>
#include <map>
#include <utility>

#include "hoilcd/bench/evaluation/json_number.h"
#include "hoilcd/core/util/stats.h"

namespace hoilcd {
namespace {

// The median of a statistic over `frames`, its NaN values left out.
double KnownMedian(const std::vector<const FrameStatistics*>& frames, double FrameStatistics::*member) {
  std::vector<double> values;
  for (const FrameStatistics* s : frames) {
    if (std::isfinite(s->*member)) values.push_back(s->*member);
  }
  return Median(std::move(values));
}

}  // namespace

std::vector<FrameSizeGroup> GroupByFrameSize(const std::vector<FrameStatistics>& statistics) {
  std::map<std::pair<int, int>, std::vector<const FrameStatistics*>> by_size;
  for (const FrameStatistics& s : statistics) by_size[{s.width_px, s.height_px}].push_back(&s);
  std::vector<FrameSizeGroup> groups;
  for (const auto& [size, frames] : by_size) {
    FrameSizeGroup g;
    g.width_px = size.first;
    g.height_px = size.second;
    g.views = static_cast<int>(frames.size());
    std::vector<const FrameStatistics*> not_blank;
    for (const FrameStatistics* s : frames) {
      if (!s->blank) not_blank.push_back(s);
    }
    g.not_blank = static_cast<int>(not_blank.size());
    g.spectrum_slope = KnownMedian(not_blank, &FrameStatistics::spectrum_slope);
    g.flat_noise_k = KnownMedian(not_blank, &FrameStatistics::flat_noise_k);
    g.flat_noise_lag1 = KnownMedian(not_blank, &FrameStatistics::flat_noise_lag1);
    groups.push_back(g);
  }
  // std::map gave them by width then height; stable: equal counts keep that order.
  std::stable_sort(groups.begin(), groups.end(),
                   [](const FrameSizeGroup& a, const FrameSizeGroup& b) { return a.views > b.views; });
  return groups;
}

nlohmann::json FrameSizeGroupsJson(const std::vector<FrameSizeGroup>& groups) {
  nlohmann::json out = nlohmann::json::array();
  for (const FrameSizeGroup& g : groups) {
    out.push_back({{"width_px", g.width_px},
                   {"height_px", g.height_px},
                   {"views", g.views},
                   {"views_not_blank", g.not_blank},
                   {"spectrum_slope_median", JsonNumber(g.spectrum_slope)},
                   {"flat_noise_k_median", JsonNumber(g.flat_noise_k)},
                   {"flat_noise_lag1_median", JsonNumber(g.flat_noise_lag1)}});
  }
  return out;
}

}  // namespace hoilcd
