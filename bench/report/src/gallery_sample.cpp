#include "hoilcd/bench/report/gallery_sample.h"

#include <algorithm>
#include <map>
#include <set>
#include <tuple>

namespace hoilcd {

std::string GalleryOutcome(const QueryRecord& record) {
  if (!record.scored) return "";
  return record.top1_is_true_match ? "hit" : "miss";
}

std::vector<size_t> SampleGallery(const std::vector<const std::vector<QueryRecord>*>& records,
                                  const std::vector<QueryConditions>& conditions,
                                  const std::vector<std::string>& stratifications, int per_group) {
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
  std::set<size_t> chosen;
  for (const auto& [group, members] : groups) {
    const size_t n = members.size(), k_max = static_cast<size_t>(per_group);
    if (n <= k_max) {
      chosen.insert(members.begin(), members.end());
      continue;
    }
    for (size_t k = 0; k < k_max; ++k) chosen.insert(members[(2 * k + 1) * n / (2 * k_max)]);
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
