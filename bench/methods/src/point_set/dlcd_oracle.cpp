// dlcd-oracle (a diagnostic, not the paper's): DLCD's HOI points taken from the true people (the
// EXR's person class as the mask, persons.json's boxes and ids as the tracks) instead of the
// detector and ByteTrack, then DLCD's matching. Against dlcd it isolates detection and tracking
// from the HOI landmark itself.
#include "point_set/point_set_method.h"

namespace hoilcd {
namespace {

class DlcdOracle : public PointSetMethod {
 public:
  DlcdOracle() : PointSetMethod(FrontEnd::kTruePersons, /*lo=*/false) {}
  std::string Name() const override { return "dlcd-oracle"; }
  std::string Description() const override {
    return "diagnostic: DLCD on the true people (ground-truth masks, boxes and ids; no detector, no tracker)";
  }
};

}  // namespace

std::unique_ptr<LoopClosureMethod> MakeDlcdOracleMethod() { return std::make_unique<DlcdOracle>(); }

}  // namespace hoilcd
