#include "hoilcd/bench/methods.h"

#include <algorithm>
#include <sstream>

#include "hoilcd/core/error.h"

namespace hoilcd {

const std::vector<MethodInfo>& MethodCatalog() {
  static const std::vector<MethodInfo> catalog = {
      {"slcd", "static landmarks: GFTT corner coordinates, MNN + vertical filter + RANSAC homography inliers", true},
      {"dlcd", "dynamic landmarks: HOI points (bottom contour of tracked people) + the same matching", true},
      {"fusion", "reciprocal rank fusion of SLCD and DLCD (k = 0)", true},
      {"slcd-lo", "SLCD with locally optimised RANSAC (least-squares refits on the inliers)", false},
      {"dlcd-lo", "DLCD with locally optimised RANSAC", false},
      {"dlcd-track", "track-aware DLCD: correspondences between the HOI contours of paired people", false},
      {"fusion-tc", "fusion with temporal consistency (consecutive queries must agree)", false},
      {"thumb", "global baseline: patch-normalised thumbnail correlation (SeqSLAM-style)", false},
      {"thumb-seq", "thumbnail correlation with SeqSLAM sequence matching", false},
  };
  return catalog;
}

const MethodInfo& FindMethod(const std::string& name) {
  const auto& catalog = MethodCatalog();
  const auto it = std::find_if(catalog.begin(), catalog.end(),
                               [&](const MethodInfo& m) { return m.name == name; });
  HOILCD_CHECK_MSG(it != catalog.end(), "unknown method " << name);
  return *it;
}

std::vector<std::string> DefaultMethods() {
  std::vector<std::string> out;
  for (const MethodInfo& m : MethodCatalog()) out.push_back(m.name);
  return out;
}

std::vector<std::string> ParseMethodList(const std::string& csv) {
  std::vector<std::string> out;
  std::stringstream ss(csv);
  std::string name;
  auto add = [&](const std::string& n) {
    if (std::find(out.begin(), out.end(), n) == out.end()) out.push_back(n);
  };
  while (std::getline(ss, name, ',')) {
    name.erase(0, name.find_first_not_of(" \t"));
    name.erase(name.find_last_not_of(" \t") + 1);
    if (name.empty()) continue;
    if (name == "all") {
      for (const MethodInfo& m : MethodCatalog()) add(m.name);
      continue;
    }
    if (name == "paper") {
      for (const MethodInfo& m : MethodCatalog())
        if (m.from_paper) add(m.name);
      continue;
    }
    const auto& catalog = MethodCatalog();
    if (std::none_of(catalog.begin(), catalog.end(), [&](const MethodInfo& m) { return m.name == name; })) {
      std::string known;
      for (const MethodInfo& m : catalog) known += (known.empty() ? "" : ", ") + m.name;
      throw InputError("--methods", "unknown method '" + name + "' (known: " + known + ", paper, all)");
    }
    add(name);
  }
  if (out.empty()) throw InputError("--methods", "at least one method name");
  return out;
}

}  // namespace hoilcd
