// The paper's fusion: reciprocal rank fusion of SLCD's and DLCD's rankings of each database.
#include <chrono>

#include "hoilcd/bench/methods/loop_closure_method.h"
#include "hoilcd/core/place_recognition/rank_fusion.h"

namespace hoilcd {
namespace {

// fusion's own options (--param fusion.k=60).
struct FusionOptions {
  double k;  // reciprocal rank fusion constant: score 1 / (k + rank) (paper: 0)

  static const OptionTable<FusionOptions>& Table() {
    static const OptionTable<FusionOptions> table = OptionTable<FusionOptions>().Add(
        "k", &FusionOptions::k, 0.0, "", OptionRange::Any().AtLeast(0),
        "reciprocal rank fusion constant: each ranking adds 1 / (k + rank) (paper: 0)");
    return table;
  }
};

class Fusion : public LoopClosureMethod {
 public:
  std::string Name() const override { return "fusion"; }
  std::string Description() const override { return "reciprocal rank fusion of SLCD and DLCD"; }
  bool FromPaper() const override { return true; }
  std::vector<std::string> Inputs() const override { return {"slcd", "dlcd"}; }
  bool Online() const override { return true; }
  std::unique_ptr<MethodOptions> Options() const override {
    return std::make_unique<OptionsOf<FusionOptions>>(FusionOptions::Table());
  }
  MethodScores Score(const MethodContext& c) const override {
    using Clock = std::chrono::steady_clock;
    const MethodScores& s = c.Input("slcd");
    const MethodScores& d = c.Input("dlcd");
    const size_t n = c.queries().size();
    MethodScores out;
    out.scores.resize(n);
    out.extract_ms.resize(n);
    out.match_ms.resize(n);
    for (size_t i = 0; i < n; ++i) {
      const auto t = Clock::now();
      out.scores[i] = ReciprocalRankFusionOfScores({s.scores[i], d.scores[i]}, c.Own<FusionOptions>().k);
      // Fusion costs both methods' extraction and matching plus the fusion itself.
      out.extract_ms[i] = s.extract_ms[i] + d.extract_ms[i];
      out.match_ms[i] =
          s.match_ms[i] + d.match_ms[i] + std::chrono::duration<double, std::milli>(Clock::now() - t).count();
    }
    return out;
  }
};

}  // namespace

std::unique_ptr<LoopClosureMethod> MakeFusionMethod() { return std::make_unique<Fusion>(); }

}  // namespace hoilcd
