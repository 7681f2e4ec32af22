// SLCD (the paper's static landmarks): GFTT corner coordinates of every frame, matched by MNN,
// the vertical filter and RANSAC homography inliers.
#include "point_set/point_set_method.h"

namespace hoilcd {
namespace {

class Slcd : public PointSetMethod {
 public:
  Slcd() : PointSetMethod(FrontEnd::kKeypoints, /*lo=*/false) {}
  std::string Name() const override { return "slcd"; }
  std::string Description() const override {
    return "static landmarks: GFTT corner coordinates, MNN + vertical filter + RANSAC homography inliers";
  }
  bool FromPaper() const override { return true; }
};

}  // namespace

std::unique_ptr<LoopClosureMethod> MakeSlcdMethod() { return std::make_unique<Slcd>(); }

}  // namespace hoilcd
