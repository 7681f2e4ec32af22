// The robust loop that drives any estimator (COLMAP's optim/ransac.h and loransac.h in one):
// exactly `trials` hypotheses from keyed samples, each scored by its inlier count, with optional
// LO-RANSAC least-squares refits of each new best model (Chum 2003). The estimator is a template
// parameter, so the loop compiles with its model and a second model reuses it without a copy.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "hoilcd/core/optim/ransac_sampler.h"
#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

// Defaults and ranges: Table() in ransac.cpp.
struct RansacOptions {
  int trials;                      // exact number of hypotheses (paper), no adaptive stop
  bool redraw_degenerate_samples;  // a degenerate sample is redrawn (up to 10 draws per trial on
                                   // average) instead of using up its trial
  double inlier_threshold_px;      // reprojection error bound, px
  int local_optimisation_refits;   // 0 = plain RANSAC (paper); >0 = LO-RANSAC least-squares
                                   // refits on the inlier set of each new best model

  RansacOptions();  // the registered defaults
  // Every field once: name, default, unit, range, description.
  static const OptionTable<RansacOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

// Upper bound on RansacOptions::trials: the sample counters (4 per draw) stay below 2^32.
constexpr int kRansacMaxTrials = 10'000'000;
// With redraw_degenerate_samples, at most trials * this many samples are drawn in all.
constexpr int64_t kRansacMaxDrawsPerTrial = 10;

// The models an estimator solves from the eight samples of a SampleBatch, one per lane.
template <int kModelSize>
struct ModelBatch {
  float model[kModelSize][kRansacLanes];
  int32_t valid[kRansacLanes];  // 0 if the lane's sample gives no model
};

// The loop drives an estimator E with static members (HomographyEstimator in core/estimators is
// one; tests/core/optim/ransac_test.cpp has a translation):
//   kSampleSize (1 to 4: matches in a minimal sample), kModelSize (floats in a model),
//   kNoModel[kModelSize] (the model reported when nothing fits),
//   Data: the matches as E's kernels read them, with an `int count`;
//   DrawAndScreen(sampler, first_draw, data, batch*, keep[8]): sampler.DrawBatch, then keep[b] =
//     -1 if sample b may give a model, 0 if not (a cheap test, so that only survivors are solved).
//     Drawing is E's call so that E's vector clone of this function (target_clones, which clang
//     does not allow on templates) inlines the sampler together with E's screening;
//   Solve(batch, data, ModelBatch<kModelSize>*): the models of the eight samples;
//   CountInliers(model, data, threshold_sq, bar): the inlier count, or any count <= bar once it
//     cannot exceed bar; MarkInliers(model, data, threshold_sq, mask): one 0/1 entry per match;
//   Refit(data, mask, model*): least-squares fit to the masked matches; false if degenerate.
// threshold_sq is inlier_threshold_px² in float. Sample d of a call is the first kSampleSize
// indices of RansacSample(seed, d, count); a model must not depend on the order of its sample.

// The loop on one set of matches: the best model's inlier count, its model in best_model
// (kModelSize floats; kNoModel below kSampleSize matches or when nothing fits). Options are not
// re-checked.
template <typename E>
int RunRansac(const typename E::Data& data, const RansacOptions& options, uint64_t seed, float* best_model);

// RunRansac's inlier counts under several variants of the options at once, reusing scratch
// buffers between calls (one per thread). Variants with the same trials and
// redraw_degenerate_samples draw the same samples, so those are drawn and solved once and the
// hypotheses scored under each variant's threshold and refits: inliers[v] equals
// RunRansac(data, variants[v], seed, ...). prepare() lays out E::Data for count matches; it is
// called only at count >= kSampleSize and timed as the first stream's drawing. When alone_ns is
// not null (then total_ns must not be), alone_ns[v] gets what variant v costs alone (drawing and
// solving its samples and its own scoring) and *total_ns the whole call, in ns; both are 0 below
// kSampleSize matches. A stream stops early once every match is an inlier of each of its
// variants' best models: nothing later can change their results.
template <typename E>
class RansacVariants {
 public:
  template <typename Prepare>
  void Count(int count, const Prepare& prepare, const RansacOptions* variants, int num_variants, uint64_t seed,
             int* inliers, int64_t* alone_ns, int64_t* total_ns);
  // Hypotheses the last Count drew and solved, over all its streams.
  int hypotheses_scored() const { return hypotheses_scored_; }

 private:
  std::vector<std::vector<uint8_t>> lo_masks_;  // one per variant
  std::vector<float> hypotheses_;               // one chunk of a stream
  std::vector<char> scored_;                    // per variant: already in a group
  int hypotheses_scored_ = 0;
};

}  // namespace hoilcd

#include "hoilcd/core/optim/ransac_loop.h"  // the templates' definitions
