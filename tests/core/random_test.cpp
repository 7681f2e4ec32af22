// The 256-bit vector of the lane test only passes through always-inline functions.
#pragma GCC diagnostic ignored "-Wpsabi"

#include "hoilcd/core/random.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

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
