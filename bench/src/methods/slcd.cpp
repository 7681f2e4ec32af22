// SLCD (the paper's static landmarks): GFTT corner coordinates of every frame, matched by MNN,
// the vertical filter and RANSAC homography inliers.
#include "hoilcd/bench/runner.h"
#include "point_set_scoring.h"

namespace hoilcd {
namespace {

class Slcd : public LoopClosureMethod {
 public:
  std::string Name() const override { return "slcd"; }
  std::string Description() const override {
    return "static landmarks: GFTT corner coordinates, MNN + vertical filter + RANSAC homography inliers";
  }
  bool FromPaper() const override { return true; }
  ShownFeatures Features() const override { return ShownFeatures::kKeypoints; }
  std::set<FrontEnd> FrontEnds() const override { return {FrontEnd::kKeypoints}; }
  MethodScores Score(const MethodContext& c) const override {
    return ScorePointSets(c, Name(), c.front_ends.keypoint_index, c.options.ransac, c.front_ends.keypoints_ms);
  }
};

}  // namespace

std::unique_ptr<LoopClosureMethod> MakeSlcdMethod() { return std::make_unique<Slcd>(); }

}  // namespace hoilcd
