// Before the includes: the sampler's 256-bit lanes run here without a vector clone (GCC notes
// the AVX ABI at random.h's CounterWord).
#pragma GCC diagnostic ignored "-Wpsabi"

#include "hoilcd/core/optim/ransac_sampler.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

namespace hoilcd {
namespace {

TEST(RansacSample, UniformOverOrderedFourTuplesOfDistinctIndices) {
  // n = 6: 360 ordered 4-tuples of distinct indices, 1000 expected draws each.
  constexpr uint32_t kN = 6;
  std::vector<int> counts(kN * kN * kN * kN, 0);
  constexpr uint32_t kDraws = 360000;
  for (uint32_t d = 0; d < kDraws; ++d) {
    uint32_t idx[4];
    RansacSample(/*seed=*/77, d, kN, idx);
    for (int a = 0; a < 4; ++a) {
      ASSERT_LT(idx[a], kN);
      for (int b = 0; b < a; ++b) ASSERT_NE(idx[a], idx[b]) << "draw " << d;
    }
    ++counts[((idx[0] * kN + idx[1]) * kN + idx[2]) * kN + idx[3]];
  }
  double chi_square = 0;
  int tuples = 0;
  for (int c : counts) {
    if (c == 0) continue;
    ++tuples;
    chi_square += (c - 1000.0) * (c - 1000.0) / 1000.0;
  }
  EXPECT_EQ(tuples, 360);
  // 359 degrees of freedom: mean 359, standard deviation 26.8; this bound is 6 sigma.
  EXPECT_LT(chi_square, 520.0);
}

TEST(RansacSample, RejectionPathStaysDistinctAndUnbiased) {
  // n = 3 * 2^30: the first digit is floor(3 w / 4) of a 32-bit word w, so without the rejection
  // test digits divisible by 3 would get two words each and the others one (1/2 of the draws
  // instead of 1/3); with it a quarter of the words are rejected and redrawn under a new key.
  constexpr uint32_t kN = 3u << 30;
  int by_residue[3] = {0, 0, 0};
  constexpr int kDraws = 30000;
  for (uint32_t d = 0; d < kDraws; ++d) {
    uint32_t idx[4];
    RansacSample(/*seed=*/5, d, kN, idx);
    for (int a = 0; a < 4; ++a) {
      ASSERT_LT(idx[a], kN);
      for (int b = 0; b < a; ++b) ASSERT_NE(idx[a], idx[b]);
    }
    ++by_residue[idx[0] % 3];
  }
  // Binomial(30000, 1/3): standard deviation 82; the bound is 6 sigma.
  for (int count : by_residue) EXPECT_NEAR(count, kDraws / 3, 6 * 82);
}

TEST(RansacSample, DifferentSeedsGiveDifferentStreams) {
  int same = 0;
  for (uint32_t d = 0; d < 1000; ++d) {
    uint32_t a[4], b[4];
    RansacSample(1, d, 200, a);
    RansacSample(2, d, 200, b);
    same += std::equal(a, a + 4, b) ? 1 : 0;
  }
  EXPECT_LE(same, 2);
}

TEST(RansacSampler, EachLaneOfABatchIsTheScalarDrawOfItsIndex) {
  // 3 * 2^30 matches: a quarter of the words are rejected, so the lanes' fix-up path runs too.
  for (const uint32_t n : {4u, 5u, 37u, 200u, 3u << 30}) {
    for (const uint64_t seed : {0ull, 9ull, 0xfeedfacecafebeefull}) {
      const RansacSampler sampler(seed, n, 4);
      for (const uint32_t first_draw : {0u, 8u, 1000u, 12345u}) {
        SampleBatch batch;
        sampler.DrawBatch(first_draw, &batch);
        for (int b = 0; b < kRansacLanes; ++b) {
          uint32_t idx[4];
          RansacSample(seed, first_draw + b, n, idx);
          for (int k = 0; k < 4; ++k) EXPECT_EQ(batch[k][b], idx[k]) << "n " << n << " lane " << b;
        }
      }
    }
  }
}

TEST(RansacSampler, SmallerSamplesAreThePrefixOfTheFourIndexDrawAndNeedOnlyTheirSize) {
  for (int size = 1; size <= 3; ++size) {
    const RansacSampler sampler(21, 50, size);
    SampleBatch batch;
    sampler.DrawBatch(16, &batch);
    for (int b = 0; b < kRansacLanes; ++b) {
      uint32_t idx[4];
      RansacSample(21, 16 + b, 50, idx);
      for (int k = 0; k < size; ++k) EXPECT_EQ(batch[k][b], idx[k]);
    }
    // As many matches as the sample holds: every draw is an ordering of all of them.
    const RansacSampler tight(21, static_cast<uint32_t>(size), size);
    tight.DrawBatch(0, &batch);
    for (int b = 0; b < kRansacLanes; ++b) {
      std::vector<uint32_t> drawn;
      for (int k = 0; k < size; ++k) drawn.push_back(batch[k][b]);
      std::sort(drawn.begin(), drawn.end());
      for (int k = 0; k < size; ++k) EXPECT_EQ(drawn[k], static_cast<uint32_t>(k));
    }
  }
  EXPECT_THROW(RansacSampler(1, 2, 3), std::logic_error);
  EXPECT_THROW(RansacSampler(1, 10, 5), std::logic_error);
}

}  // namespace
}  // namespace hoilcd
