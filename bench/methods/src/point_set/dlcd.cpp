// DLCD (the paper's dynamic landmarks): HOI points, the bottom contour of tracked people, matched
// like SLCD's corners.
#include "point_set/point_set_method.h"

namespace hoilcd {
namespace {

class Dlcd : public PointSetMethod {
 public:
  Dlcd() : PointSetMethod(FrontEnd::kPersons, /*lo=*/false) {}
  std::string Name() const override { return "dlcd"; }
  std::string Description() const override {
    return "dynamic landmarks: HOI points (bottom contour of tracked people) + the same matching";
  }
  bool FromPaper() const override { return true; }
};

}  // namespace

std::unique_ptr<LoopClosureMethod> MakeDlcdMethod() { return std::make_unique<Dlcd>(); }

}  // namespace hoilcd
