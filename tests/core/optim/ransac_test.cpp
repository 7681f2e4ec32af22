// Before the includes: the translation below draws with the sampler's 256-bit lanes without a
// vector clone (GCC notes the AVX ABI at random.h's CounterWord).
#pragma GCC diagnostic ignored "-Wpsabi"

#include "hoilcd/core/optim/ransac.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "hoilcd/core/util/random.h"
#include "option_properties.h"

namespace hoilcd {
namespace {

// A second model for the loop: the 2-D translation query = reference + t, one match per sample,
// refit as the mean offset of the inliers. Plain scalar code, no vector clones.
struct TranslationEstimator {
  static constexpr int kSampleSize = 1;
  static constexpr int kModelSize = 2;
  static constexpr float kNoModel[kModelSize] = {0, 0};

  struct Data {
    const float *ref_x, *ref_y, *query_x, *query_y;
    int count;
  };

  static void DrawAndScreen(const RansacSampler& sampler, uint32_t first_draw, const Data&, SampleBatch* batch,
                            int32_t keep[kRansacLanes]) {
    sampler.DrawBatch(first_draw, batch);
    std::fill(keep, keep + kRansacLanes, -1);  // any one match gives a translation
  }
  static void Solve(const SampleBatch& batch, const Data& data, ModelBatch<kModelSize>* out) {
    for (int b = 0; b < kRansacLanes; ++b) {
      const uint32_t i = batch[0][b];
      out->model[0][b] = data.query_x[i] - data.ref_x[i];
      out->model[1][b] = data.query_y[i] - data.ref_y[i];
      out->valid[b] = 1;
    }
  }
  static bool IsInlier(const float* t, const Data& data, float threshold_sq, int i) {
    const float dx = data.ref_x[i] + t[0] - data.query_x[i], dy = data.ref_y[i] + t[1] - data.query_y[i];
    return dx * dx + dy * dy < threshold_sq;
  }
  static int CountInliers(const float* t, const Data& data, float threshold_sq, int /*bar*/) {
    int inliers = 0;
    for (int i = 0; i < data.count; ++i) inliers += IsInlier(t, data, threshold_sq, i) ? 1 : 0;
    return inliers;
  }
  static void MarkInliers(const float* t, const Data& data, float threshold_sq, uint8_t* mask) {
    for (int i = 0; i < data.count; ++i) mask[i] = IsInlier(t, data, threshold_sq, i) ? 1 : 0;
  }
  static bool Refit(const Data& data, const uint8_t* mask, float* t) {
    double sum_x = 0, sum_y = 0;
    int n = 0;
    for (int i = 0; i < data.count; ++i) {
      if (!mask[i]) continue;
      sum_x += data.query_x[i] - data.ref_x[i];
      sum_y += data.query_y[i] - data.ref_y[i];
      ++n;
    }
    if (n == 0) return false;
    t[0] = static_cast<float>(sum_x / n);
    t[1] = static_cast<float>(sum_y / n);
    return true;
  }
};

// count matches, the first num_inliers shifted by exactly (12.5, -3.25) (coordinates on a
// quarter-pixel grid, so every offset is exact in float), the others off it by 20-60 px.
struct TranslationProblem {
  std::vector<float> ref_x, ref_y, query_x, query_y;
  TranslationEstimator::Data data() const {
    return {ref_x.data(), ref_y.data(), query_x.data(), query_y.data(), static_cast<int>(ref_x.size())};
  }
};

TranslationProblem MakeTranslationProblem(int count, int num_inliers, uint64_t seed) {
  Rng rng = KeyedRng(seed, "test.ransac.translation");
  TranslationProblem p;
  for (int i = 0; i < count; ++i) {
    const float x = std::round(static_cast<float>(rng.Uniform(0, 256)) * 4) / 4;
    const float y = std::round(static_cast<float>(rng.Uniform(0, 192)) * 4) / 4;
    float dx = 12.5f, dy = -3.25f;
    if (i >= num_inliers) {
      const double angle = rng.Uniform(0, 2 * M_PI), radius = rng.Uniform(20, 60);
      dx += static_cast<float>(radius * std::cos(angle));
      dy += static_cast<float>(radius * std::sin(angle));
    }
    p.ref_x.push_back(x);
    p.ref_y.push_back(y);
    p.query_x.push_back(x + dx);
    p.query_y.push_back(y + dy);
  }
  return p;
}

TEST(RunRansac, ASecondModelReusesTheLoopAndRecoversATranslationExactlyFromInliersAndOutliers) {
  const TranslationProblem problem = MakeTranslationProblem(100, 40, 3);
  RansacOptions plain, refitted;
  refitted.local_optimisation_refits = 2;
  for (const RansacOptions& options : {plain, refitted}) {
    float t[2] = {-1, -1};
    EXPECT_EQ(RunRansac<TranslationEstimator>(problem.data(), options, 11, t), 40);
    EXPECT_EQ(t[0], 12.5f);
    EXPECT_EQ(t[1], -3.25f);
  }
}

TEST(RunRansac, BelowOneSampleOfMatchesGivesNoModelAndZeroInliers) {
  const TranslationProblem empty;
  float t[2] = {-1, -1};
  EXPECT_EQ(RunRansac<TranslationEstimator>(empty.data(), RansacOptions{}, 1, t), 0);
  EXPECT_EQ(t[0], 0.0f);
  EXPECT_EQ(t[1], 0.0f);
}

TEST(RansacVariants, EachVariantOfASecondModelCountsWhatItsOwnRunCounts) {
  std::vector<RansacOptions> variants(4);
  variants[1].local_optimisation_refits = 2;
  variants[2].inlier_threshold_px = 0.5;
  variants[3].trials = 3, variants[3].redraw_degenerate_samples = false;
  RansacVariants<TranslationEstimator> counter;
  for (const uint64_t seed : {1u, 2u, 3u}) {
    const TranslationProblem problem = MakeTranslationProblem(60, 15, seed);
    std::vector<int> inliers(variants.size(), -1);
    counter.Count(
        60, [&] { return problem.data(); }, variants.data(), static_cast<int>(variants.size()), seed, inliers.data(),
        nullptr, nullptr);
    for (size_t v = 0; v < variants.size(); ++v) {
      float t[2];
      EXPECT_EQ(inliers[v], RunRansac<TranslationEstimator>(problem.data(), variants[v], seed, t)) << v;
    }
  }
}

TEST(RansacOptions, HoldsThePapersDefaultsFromItsTableAndChecksEveryBound) {
  const RansacOptions options;
  EXPECT_EQ(options.trials, 100);  // paper, section 5.2
  EXPECT_EQ(options.inlier_threshold_px, 5.0);
  EXPECT_EQ(options.local_optimisation_refits, 0);
  ExpectConstructedHoldsTheTableDefaults<RansacOptions>();
  EXPECT_EQ(ExpectEveryBoundCrossedIsNamedByCheck<RansacOptions>(), 5);
}

}  // namespace
}  // namespace hoilcd
