// RANSAC's samples: draw d of a stream is up to four distinct indices in [0, n), uniform over
// ordered tuples, from the counter-based words of the keyed RNG (random.h). Eight draws run at once
// in vector lanes and give what one-by-one draws give, so results never depend on the batching.
#pragma once

#include <cstdint>
#include <cstring>

#include "hoilcd/core/util/random.h"

namespace hoilcd {

// Lanes of the loop's vectors: samples are drawn, screened and solved eight at a time.
constexpr int kRansacLanes = 8;
// GCC vector extensions; a build without AVX lowers them to two SSE halves.
using Floats8 = float __attribute__((vector_size(32)));
using Ints8 = int32_t __attribute__((vector_size(32)));
using Uints8 = uint32_t __attribute__((vector_size(32)));

// Eight samples of up to four match indices each: batch[k][b] is index k of sample b (lane b).
using SampleBatch = uint32_t[4][kRansacLanes];

// Digit k of draw d is uniform in [0, n - k), by Lemire's multiply-shift on the 32-bit word
// CounterWord(key, 4 d + k) with the exact rejection test, and is bumped past the k indices taken
// before it. A rejected word (probability below n / 2^32) is replaced by the same counter's word
// under the key MixBits(key + attempt). Index k depends only on digits 0..k, so a sample of size s
// is the first s indices of the four-index draw (which needs n >= 4) and needs only n >= s.
class RansacSampler {
 public:
  // Samples of `size` (1 to 4) indices among n >= size matches, from the stream `key`.
  RansacSampler(uint64_t key, uint32_t n, int size);

  // Draws first_draw .. first_draw + 7 into the lanes of *batch; rows from `size` on are not
  // indices. Always inlined, so an estimator's vector clone (its DrawAndScreen) draws with its own
  // instruction set. A template only so that it is compiled where it is called: elsewhere the
  // 256-bit code (and GCC's -Wpsabi note on it) never appears.
  template <typename Lanes = Uints8>
  [[gnu::always_inline]] inline void DrawBatch(uint32_t first_draw, SampleBatch* batch) const;

  // Digit k of draw `draw`, one lane at a time (also the fix-up of rejected vector lanes).
  uint32_t Digit(uint32_t draw, int k) const;

 private:
  uint64_t key_;
  uint32_t range_[4];         // n - k; 1 for digits past the sample's size
  uint32_t reject_below_[4];  // 2^32 mod range: low words below this are rejected
};

// Draw `draw` of the stream `seed` over n >= 4 matches: four distinct indices in [0, n), uniform
// over ordered 4-tuples; the scalar form of RansacSampler::DrawBatch (tested for uniformity).
void RansacSample(uint64_t seed, uint32_t draw, uint32_t n, uint32_t idx[4]);

namespace internal {

// Digits (digit[k] in [0, n - k)) to distinct indices: each digit is bumped past every taken index
// at or below it, smallest taken first. Written once for uint32_t and Uints8.
template <typename U32>
[[gnu::always_inline]] inline void DistinctFromDigits(const U32 digit[4], U32 idx[4]) {
  const U32 i0 = digit[0];
  const U32 i1 = digit[1] >= i0 ? digit[1] + 1 : digit[1];
  const U32 a = i0 < i1 ? i0 : i1, b = i0 < i1 ? i1 : i0;
  U32 i2 = digit[2] >= a ? digit[2] + 1 : digit[2];
  i2 = i2 >= b ? i2 + 1 : i2;
  const U32 lo = a < i2 ? a : i2, hi = b < i2 ? i2 : b;
  const U32 mid = i0 + i1 + i2 - lo - hi;
  U32 i3 = digit[3] >= lo ? digit[3] + 1 : digit[3];
  i3 = i3 >= mid ? i3 + 1 : i3;
  i3 = i3 >= hi ? i3 + 1 : i3;
  idx[0] = i0;
  idx[1] = i1;
  idx[2] = i2;
  idx[3] = i3;
}

}  // namespace internal

template <typename Lanes>
void RansacSampler::DrawBatch(uint32_t first_draw, SampleBatch* batch) const {
  using Uint64s4 = uint64_t __attribute__((vector_size(32)));
  using Uints4 = uint32_t __attribute__((vector_size(16)));
  const Lanes draw = Lanes{0, 1, 2, 3, 4, 5, 6, 7} + first_draw;
  Lanes digit[4];
  Lanes rejected = {};  // lanes with a rejected word in some digit
  for (int k = 0; k < 4; ++k) {
    const Lanes word = CounterWord<Lanes>(key_, 4 * draw + static_cast<uint32_t>(k));
    // 32 x 32 -> 64-bit products, four lanes at a time.
    const Uint64s4 low_half =
        __builtin_convertvector(__builtin_shufflevector(word, word, 0, 1, 2, 3), Uint64s4) * range_[k];
    const Uint64s4 high_half =
        __builtin_convertvector(__builtin_shufflevector(word, word, 4, 5, 6, 7), Uint64s4) * range_[k];
    const Uints4 digit_low = __builtin_convertvector(low_half >> 32, Uints4);
    const Uints4 digit_high = __builtin_convertvector(high_half >> 32, Uints4);
    const Uints4 rest_low = __builtin_convertvector(low_half, Uints4);
    const Uints4 rest_high = __builtin_convertvector(high_half, Uints4);
    digit[k] = __builtin_shufflevector(digit_low, digit_high, 0, 1, 2, 3, 4, 5, 6, 7);
    const Lanes rest = __builtin_shufflevector(rest_low, rest_high, 0, 1, 2, 3, 4, 5, 6, 7);
    rejected |= rest < reject_below_[k];
  }
  // Rejections are rare (probability below n / 2^32 per digit): one test for the whole batch.
  Lanes folded = rejected | __builtin_shufflevector(rejected, rejected, 4, 5, 6, 7, 0, 1, 2, 3);
  folded |= __builtin_shufflevector(folded, folded, 2, 3, 0, 1, 6, 7, 4, 5);
  folded |= __builtin_shufflevector(folded, folded, 1, 0, 3, 2, 5, 4, 7, 6);
  if (__builtin_expect(folded[0] != 0, 0)) {
    for (int b = 0; b < kRansacLanes; ++b) {
      if (!rejected[b]) continue;
      for (int k = 0; k < 4; ++k) digit[k][b] = Digit(first_draw + b, k);
    }
  }
  Lanes idx[4];
  internal::DistinctFromDigits(digit, idx);
  std::memcpy(batch, idx, sizeof idx);
}

}  // namespace hoilcd
