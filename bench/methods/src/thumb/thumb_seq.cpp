// SeqSLAM-style sequence matching over thumb's dense frame x frame similarity.
#include <algorithm>
#include <chrono>

#include "hoilcd/bench/methods/loop_closure_method.h"
#include "hoilcd/core/place_recognition/thumbnail_baseline.h"

namespace hoilcd {
namespace {

class ThumbSeq : public LoopClosureMethod {
 public:
  std::string Name() const override { return "thumb-seq"; }
  std::string Description() const override { return "thumbnail correlation with SeqSLAM sequence matching"; }
  std::vector<std::string> Inputs() const override { return {"thumb"}; }
  std::unique_ptr<MethodOptions> Options() const override {
    static const OptionTable<SeqSlamOptions> table =
        SeqSlamOptions::Table().Only({"sequence_length", "velocity_steps"});
    return std::make_unique<OptionsOf<SeqSlamOptions>>(table);
  }
  MethodScores Score(const MethodContext& c) const override {
    using Clock = std::chrono::steady_clock;
    const MethodScores& thumb = c.Input("thumb");
    const auto t = Clock::now();
    const auto seq = SequenceScores(thumb.dense, c.Own<SeqSlamOptions>(), c.threads);
    const double seq_ms =
        std::chrono::duration<double, std::milli>(Clock::now() - t).count() / std::max(1, c.dataset.num_frames());
    MethodScores out;
    for (const Query& q : c.queries()) {
      out.scores.emplace_back();
      for (int r : q.database) out.scores.back().push_back(seq[q.frame][r]);
    }
    out.extract_ms = thumb.extract_ms;
    out.match_ms = thumb.match_ms;
    for (double& v : out.match_ms) v += seq_ms;
    return out;
  }
};

}  // namespace

std::unique_ptr<LoopClosureMethod> MakeThumbSeqMethod() { return std::make_unique<ThumbSeq>(); }

}  // namespace hoilcd
