// Vector draws of the keyed streams declared in random.h.
#include "hoilcd/core/util/random.h"

#include <algorithm>

#include <Eigen/Core>

#include "hoilcd/core/util/error.h"

namespace hoilcd {

void KeyedNormals(uint64_t key, int64_t first, int count, float* out) {
  HOILCD_CHECK(first >= 0 && count >= 0);
  if (count == 0) return;
  HOILCD_CHECK_MSG(first + count <= (int64_t{1} << 32), "index range beyond 2^32");
  // Pairs are drawn in blocks of kBlock: fixed-size Eigen arrays stay on the stack and their
  // log, sqrt, sin and cos run in vector lanes.
  constexpr int kBlock = 64;
  using Block = Eigen::Array<float, kBlock, 1>;
  constexpr float kWordScale = 1.0f / 16777216.0f;  // 24-bit words to [0, 1)
  constexpr float kTwoPi = 6.28318530717958647692f;
  const int64_t first_pair = first / 2, last_pair = (first + count - 1) / 2;
  for (int64_t block_pair = first_pair; block_pair <= last_pair; block_pair += kBlock) {
    const int pairs = static_cast<int>(std::min<int64_t>(kBlock, last_pair - block_pair + 1));
    Block u1, u2;
    for (int j = 0; j < kBlock; ++j) {
      const uint32_t counter = 2 * static_cast<uint32_t>(block_pair + std::min(j, pairs - 1));
      // u1 in (0, 1] so that its log is finite; u2 in [0, 1).
      u1[j] = static_cast<float>((CounterWord(key, counter) >> 8) + 1) * kWordScale;
      u2[j] = static_cast<float>(CounterWord(key, counter + 1) >> 8) * kWordScale;
    }
    const Block radius = (-2.0f * u1.log()).sqrt();
    const Block angle = kTwoPi * u2;
    const Block cosine = radius * angle.cos(), sine = radius * angle.sin();
    const int64_t begin = std::max(first, 2 * block_pair);
    const int64_t end = std::min(first + count, 2 * (block_pair + pairs));
    for (int64_t i = begin; i < end; ++i) {
      const int j = static_cast<int>(i / 2 - block_pair);
      out[i - first] = (i % 2 == 0) ? cosine[j] : sine[j];
    }
  }
}

}  // namespace hoilcd
