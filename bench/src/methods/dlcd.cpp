// DLCD (the paper's dynamic landmarks): HOI points, the bottom contour of tracked people, matched
// like SLCD's corners.
#include "hoilcd/bench/runner.h"
#include "point_set_scoring.h"

namespace hoilcd {
namespace {

class Dlcd : public LoopClosureMethod {
 public:
  std::string Name() const override { return "dlcd"; }
  std::string Description() const override {
    return "dynamic landmarks: HOI points (bottom contour of tracked people) + the same matching";
  }
  bool FromPaper() const override { return true; }
  ShownFeatures Features() const override { return ShownFeatures::kHoiPoints; }
  std::set<FrontEnd> FrontEnds() const override { return {FrontEnd::kPersons}; }
  MethodScores Score(const MethodContext& c) const override {
    return ScorePointSets(c, Name(), c.front_ends.hoi_index, c.options.ransac, c.front_ends.persons_ms);
  }
};

}  // namespace

std::unique_ptr<LoopClosureMethod> MakeDlcdMethod() { return std::make_unique<Dlcd>(); }

}  // namespace hoilcd
