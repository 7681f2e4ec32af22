#include "hoilcd/bench/report/gallery_sample.h"

#include <algorithm>
#include <cstdint>
#include <map>
#include <set>
#include <tuple>

#include "hoilcd/core/util/error.h"

namespace hoilcd {

std::string GalleryOutcome(const QueryRecord& record) {
  if (!record.scored) return "";
  return record.top1_is_true_match ? "hit" : "miss";
}

std::vector<size_t> SampleGallery(const std::vector<const std::vector<QueryRecord>*>& records,
                                  const std::vector<QueryConditions>& conditions,
                                  const std::vector<std::string>& stratifications, const GallerySampling& sampling) {
  HOILCD_CHECK_MSG(sampling.per_group >= 1 && sampling.min_gap_frames >= 1,
                   "gallery sampling: per_group " << sampling.per_group << ", min_gap_frames "
                                                  << sampling.min_gap_frames << " (both must be at least 1)");
  // (method, outcome, stratum) -> its queries in order.
  std::map<std::tuple<size_t, std::string, std::string>, std::vector<size_t>> groups;
  for (size_t m = 0; m < records.size(); ++m) {
    for (size_t i = 0; i < conditions.size() && i < records[m]->size(); ++i) {
      const std::string outcome = GalleryOutcome((*records[m])[i]);
      if (outcome.empty()) continue;
      groups[{m, outcome, ""}].push_back(i);
      for (const std::string& s : stratifications) {
        const std::string stratum = StratumOf(s, conditions[i]);
        if (!stratum.empty()) groups[{m, outcome, s + ": " + stratum}].push_back(i);
      }
      if (conditions[i].blank) groups[{m, outcome, "blank view"}].push_back(i);
    }
  }
  std::vector<const std::vector<size_t>*> order;
  for (const auto& group : groups) order.push_back(&group.second);
  std::stable_sort(order.begin(), order.end(), [](const auto* a, const auto* b) { return a->size() < b->size(); });
  std::set<size_t> chosen;
  std::set<int> frames;                 // of the chosen queries
  const auto is_free = [&](size_t i) {  // at least the gap from every chosen query
    const int frame = conditions[i].frame;
    const auto next = frames.lower_bound(frame - sampling.min_gap_frames + 1);
    return next == frames.end() || *next >= frame + sampling.min_gap_frames;
  };
  const size_t slots = static_cast<size_t>(sampling.per_group);
  for (const std::vector<size_t>* group : order) {
    const std::vector<size_t>& members = *group;
    const size_t n = members.size();
    std::vector<uint8_t> sampled(n);
    size_t held = 0;
    for (size_t j = 0; j < n; ++j) {
      sampled[j] = chosen.count(members[j]) > 0 ? 1 : 0;
      held += sampled[j];
    }
    for (size_t k = 0; k < slots && held < slots; ++k) {
      const size_t begin = k * n / slots, end = (k + 1) * n / slots;
      if (std::find(sampled.begin() + begin, sampled.begin() + end, 1) != sampled.begin() + end) continue;
      // The free member nearest the slot's middle, the earlier one on a tie; none: every member
      // is within the gap of a chosen query, now and later.
      const size_t middle = (2 * k + 1) * n / (2 * slots);
      size_t pick = n;
      for (size_t d = 0; d < n && pick == n; ++d) {
        if (d <= middle && !sampled[middle - d] && is_free(members[middle - d]))
          pick = middle - d;
        else if (middle + d < n && !sampled[middle + d] && is_free(members[middle + d]))
          pick = middle + d;
      }
      if (pick == n) break;
      sampled[pick] = 1;
      ++held;
      chosen.insert(members[pick]);
      frames.insert(conditions[members[pick]].frame);
    }
  }
  return {chosen.begin(), chosen.end()};
}

std::vector<std::string> StratificationsOf(const std::vector<StratumRow>& strata) {
  std::vector<std::string> out;
  for (const StratumRow& row : strata) {
    if (std::find(out.begin(), out.end(), row.stratification) == out.end()) out.push_back(row.stratification);
  }
  return out;
}

}  // namespace hoilcd
