// DLCD with locally optimised RANSAC.
#include "hoilcd/bench/runner.h"
#include "point_set_scoring.h"

namespace hoilcd {
namespace {

class DlcdLo : public LoopClosureMethod {
 public:
  std::string Name() const override { return "dlcd-lo"; }
  std::string Description() const override { return "DLCD with locally optimised RANSAC"; }
  ShownFeatures Features() const override { return ShownFeatures::kHoiPoints; }
  std::set<FrontEnd> FrontEnds() const override { return {FrontEnd::kPersons}; }
  MethodScores Score(const MethodContext& c) const override {
    return ScorePointSets(c, Name(), c.front_ends.hoi_index, LocallyOptimised(c.options), c.front_ends.persons_ms);
  }
};

}  // namespace

std::unique_ptr<LoopClosureMethod> MakeDlcdLoMethod() { return std::make_unique<DlcdLo>(); }

}  // namespace hoilcd
