// SLCD with locally optimised RANSAC: least-squares refits of the homography on its inliers.
#include "point_set/point_set_method.h"

namespace hoilcd {
namespace {

class SlcdLo : public PointSetMethod {
 public:
  SlcdLo() : PointSetMethod(FrontEnd::kKeypoints, /*lo=*/true) {}
  std::string Name() const override { return "slcd-lo"; }
  std::string Description() const override {
    return "SLCD with locally optimised RANSAC (least-squares refits on the inliers)";
  }
};

}  // namespace

std::unique_ptr<LoopClosureMethod> MakeSlcdLoMethod() { return std::make_unique<SlcdLo>(); }

}  // namespace hoilcd
