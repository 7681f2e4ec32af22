// slcd-ideal (a diagnostic, not the paper's): SLCD's corners of the noise-free true temperature
// (the EXR's T_true, before the sensor model) in the thermal PNGs' 8-bit window, then SLCD's
// matching. Against slcd it isolates the sensor (noise, fixed pattern, blur, drift, FFC, video)
// from the method.
#include "point_set/point_set_method.h"

namespace hoilcd {
namespace {

class SlcdIdeal : public PointSetMethod {
 public:
  SlcdIdeal() : PointSetMethod(FrontEnd::kIdealKeypoints, /*lo=*/false) {}
  std::string Name() const override { return "slcd-ideal"; }
  std::string Description() const override {
    return "diagnostic: SLCD on the noise-free true temperature in the same 8-bit window (an ideal sensor)";
  }
};

}  // namespace

std::unique_ptr<LoopClosureMethod> MakeSlcdIdealMethod() { return std::make_unique<SlcdIdeal>(); }

}  // namespace hoilcd
