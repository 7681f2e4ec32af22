#include "hoilcd/core/optim/ransac_sampler.h"

#include "hoilcd/core/util/error.h"

namespace hoilcd {

RansacSampler::RansacSampler(uint64_t key, uint32_t n, int size) : key_(key) {
  HOILCD_CHECK_MSG(size >= 1 && size <= 4, "a sample holds 1 to 4 indices (got " << size << ")");
  HOILCD_CHECK_MSG(n >= static_cast<uint32_t>(size),
                   "a sample of " << size << " needs n >= " << size << " matches (got " << n << ")");
  for (int k = 0; k < 4; ++k) {
    range_[k] = k < size ? n - static_cast<uint32_t>(k) : 1;
    reject_below_[k] = (0u - range_[k]) % range_[k];
  }
}

uint32_t RansacSampler::Digit(uint32_t draw, int k) const {
  const uint32_t counter = 4 * draw + static_cast<uint32_t>(k);
  for (uint64_t attempt = 0;; ++attempt) {
    const uint64_t attempt_key = attempt == 0 ? key_ : MixBits(key_ + attempt);
    const uint64_t product = static_cast<uint64_t>(CounterWord(attempt_key, counter)) * range_[k];
    if (static_cast<uint32_t>(product) >= reject_below_[k]) return static_cast<uint32_t>(product >> 32);
  }
}

void RansacSample(uint64_t seed, uint32_t draw, uint32_t n, uint32_t idx[4]) {
  HOILCD_CHECK_MSG(n >= 4, "a sample needs n >= 4 matches (got " << n << ")");
  const RansacSampler sampler(seed, n, 4);
  uint32_t digit[4];
  for (int k = 0; k < 4; ++k) digit[k] = sampler.Digit(draw, k);
  internal::DistinctFromDigits(digit, idx);
}

}  // namespace hoilcd
