#include "hoilcd/sim/assets/surface_field.h"

#include <cmath>

#include <gtest/gtest.h>

namespace hoilcd {
namespace {

TEST(ValueNoise3, StaysInRangeVariesAndIsSmoothAndStablePerKey) {
  double sum = 0, sum_sq = 0, max_step = 0;
  int n = 0, differ = 0;
  for (int i = 0; i < 4000; ++i) {
    const Eigen::Vector3f p(0.0137f * i, 0.7f + 0.0071f * i, -1.3f + 0.0029f * i);
    const float v = ValueNoise3(7, p);
    ASSERT_GE(v, -1.0f);
    ASSERT_LE(v, 1.0f);
    EXPECT_EQ(v, ValueNoise3(7, p));  // the same key and point give the same value
    differ += std::abs(v - ValueNoise3(8, p)) > 0.05f;
    // Continuity: a step of 1e-3 moves the value by a bounded slope (quintic fade: ≤ 1.875 per
    // unit per axis, so ≤ 2 × 1.875 × √3 × 1e-3 over the lattice's span of 2).
    max_step = std::max<double>(max_step, std::abs(ValueNoise3(7, p + Eigen::Vector3f::Constant(1e-3f)) - v));
    sum += v, sum_sq += v * v, ++n;
  }
  EXPECT_LT(max_step, 2 * 1.875 * std::sqrt(3.0) * 1e-3 * 1.01);
  EXPECT_NEAR(sum / n, 0.0, 0.15);
  EXPECT_GT(std::sqrt(sum_sq / n), 0.2);  // it varies, not a constant
  EXPECT_GT(differ, 3000);                // another key is another pattern
}

}  // namespace
}  // namespace hoilcd
