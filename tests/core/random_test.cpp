#include "hoilcd/core/random.h"

#include <gtest/gtest.h>

#include <cmath>

namespace hoilcd {
namespace {

TEST(KeyedRng, SameKeysGiveSameStream) {
  Rng a = KeyedRng(42, "test", 3, 7);
  Rng b = KeyedRng(42, "test", 3, 7);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(a.NextU32(), b.NextU32());
}

TEST(KeyedRng, DifferentKeysOrPurposesGiveDifferentStreams) {
  EXPECT_NE(KeyedRng(42, "test", 3, 7).NextU32(), KeyedRng(42, "test", 3, 8).NextU32());
  EXPECT_NE(KeyedRng(42, "test", 3, 7).NextU32(), KeyedRng(42, "other", 3, 7).NextU32());
  EXPECT_NE(KeyedRng(42, "test", 3, 7).NextU32(), KeyedRng(43, "test", 3, 7).NextU32());
}

TEST(Rng, NormalHasUnitVarianceAndUniformIsInRange) {
  Rng rng(1);
  double sum = 0, sum2 = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double x = rng.Normal();
    sum += x;
    sum2 += x * x;
    const double u = rng.Uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    ASSERT_LT(rng.UniformInt(7), 7u);
  }
  EXPECT_NEAR(sum / n, 0.0, 0.01);
  EXPECT_NEAR(sum2 / n, 1.0, 0.02);
}

}  // namespace
}  // namespace hoilcd
