// DLCD with locally optimised RANSAC.
#include "point_set/point_set_method.h"

namespace hoilcd {
namespace {

class DlcdLo : public PointSetMethod {
 public:
  DlcdLo() : PointSetMethod(FrontEnd::kPersons, /*lo=*/true) {}
  std::string Name() const override { return "dlcd-lo"; }
  std::string Description() const override { return "DLCD with locally optimised RANSAC"; }
};

}  // namespace

std::unique_ptr<LoopClosureMethod> MakeDlcdLoMethod() { return std::make_unique<DlcdLo>(); }

}  // namespace hoilcd
