// SLCD with locally optimised RANSAC: least-squares refits of the homography on its inliers.
#include "hoilcd/bench/runner.h"
#include "point_set_scoring.h"

namespace hoilcd {
namespace {

class SlcdLo : public LoopClosureMethod {
 public:
  std::string Name() const override { return "slcd-lo"; }
  std::string Description() const override {
    return "SLCD with locally optimised RANSAC (least-squares refits on the inliers)";
  }
  ShownFeatures Features() const override { return ShownFeatures::kKeypoints; }
  std::set<FrontEnd> FrontEnds() const override { return {FrontEnd::kKeypoints}; }
  MethodScores Score(const MethodContext& c) const override {
    return ScorePointSets(c, Name(), c.front_ends.keypoint_index, LocallyOptimised(c.options), c.front_ends.keypoints_ms);
  }
};

}  // namespace

std::unique_ptr<LoopClosureMethod> MakeSlcdLoMethod() { return std::make_unique<SlcdLo>(); }

}  // namespace hoilcd
