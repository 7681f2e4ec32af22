// The 256-bit vector of the lane test only passes through always-inline functions.
#pragma GCC diagnostic ignored "-Wpsabi"

#include "hoilcd/core/util/random.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

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

namespace hoilcd {
namespace {

TEST(CounterWord, SmallKeysGiveUnrelatedStreams) {
  // Keys 0..63 x counters 0..4095: 262144 words. Independent 32-bit words repeat about
  // n^2 / 2^33 = 8 times; streams that were permutations of each other (a key folded into the
  // counter without mixing) would repeat every word 64 times.
  std::vector<uint32_t> words;
  for (uint64_t key = 0; key < 64; ++key) {
    for (uint32_t counter = 0; counter < 4096; ++counter) words.push_back(CounterWord(key, counter));
  }
  std::sort(words.begin(), words.end());
  const auto repeats = words.size() - (std::unique(words.begin(), words.end()) - words.begin());
  EXPECT_LT(repeats, 40u);
}

TEST(CounterWord, VectorLanesEqualScalarCalls) {
  using Uints8 = uint32_t __attribute__((vector_size(32)));
  const Uints8 counters = {0, 1, 2, 3, 1000, 77777, 0xfffffffe, 0xffffffff};
  const Uints8 words = CounterWord<Uints8>(42, counters);
  for (int lane = 0; lane < 8; ++lane) EXPECT_EQ(words[lane], CounterWord<uint32_t>(42, counters[lane]));
}

}  // namespace
}  // namespace hoilcd

namespace hoilcd {
namespace {

TEST(KeyedNormals, EachValueDependsOnlyOnKeyAndIndexNotOnHowTheRangeIsSplit) {
  std::vector<float> whole(1000);
  KeyedNormals(99, 10, 1000, whole.data());
  for (const auto& [first, count] : std::vector<std::pair<int, int>>{{10, 1}, {11, 3}, {137, 200}, {500, 510}}) {
    std::vector<float> part(count);
    KeyedNormals(99, first, count, part.data());
    for (int i = 0; i < count; ++i) ASSERT_EQ(part[i], whole[first - 10 + i]) << first << "+" << i;
  }
  std::vector<float> other(1000);
  KeyedNormals(100, 10, 1000, other.data());
  EXPECT_NE(other, whole);
}

TEST(KeyedNormals, AreStandardNormalAndTheCosineAndSineOfAPairAreUncorrelated) {
  const int n = 400000;
  std::vector<float> x(n);
  KeyedNormals(7, 0, n, x.data());
  double sum = 0, sum2 = 0, sum4 = 0, pair = 0;
  int beyond_two_sigma = 0;
  for (int i = 0; i < n; ++i) {
    ASSERT_TRUE(std::isfinite(x[i]));
    sum += x[i], sum2 += x[i] * x[i], sum4 += std::pow(x[i], 4);
    beyond_two_sigma += std::abs(x[i]) > 2.0f;
    if (i % 2 == 1) pair += static_cast<double>(x[i]) * x[i - 1];
  }
  EXPECT_NEAR(sum / n, 0.0, 0.01);
  EXPECT_NEAR(sum2 / n, 1.0, 0.01);
  EXPECT_NEAR(sum4 / n, 3.0, 0.1);  // a normal's fourth moment
  EXPECT_NEAR(static_cast<double>(beyond_two_sigma) / n, 0.0455, 0.002);
  EXPECT_NEAR(pair / (n / 2), 0.0, 0.01);
}

}  // namespace
}  // namespace hoilcd
