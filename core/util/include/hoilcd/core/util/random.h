// The one RNG keying scheme: every random stream is derived from Hash(seed, purpose, keys...),
// never from a shared generator, so results do not depend on thread count or order (SPEC.md).
#pragma once

#include <cmath>
#include <cstdint>
#include <string_view>

namespace hoilcd {

// SplitMix64 finaliser: a fast, well-mixed 64-bit bijection.
constexpr uint64_t MixBits(uint64_t v) {
  v ^= v >> 31;
  v *= 0x7fb5d329728ea185ULL;
  v ^= v >> 27;
  v *= 0x81dadef4bc2dd44dULL;
  v ^= v >> 33;
  return v;
}

// FNV-1a of a purpose string, so purposes are named ("sensor.netd") rather than numbered.
constexpr uint64_t HashString(std::string_view s) {
  uint64_t h = 0xcbf29ce484222325ULL;
  for (char c : s) {
    h ^= static_cast<uint8_t>(c);
    h *= 0x100000001b3ULL;
  }
  return h;
}

constexpr uint64_t HashCombine(uint64_t h) { return MixBits(h); }
template <typename... Rest>
constexpr uint64_t HashCombine(uint64_t h, uint64_t next, Rest... rest) {
  return HashCombine(MixBits(h ^ (next + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2))), static_cast<uint64_t>(rest)...);
}

// Chris Wellons' lowbias32: a 32-bit bijection with low avalanche bias, written once for
// uint32_t and GCC vectors of uint32_t (the operators apply lane by lane).
template <typename U32>
[[gnu::always_inline]] inline U32 LowBias32(U32 x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

// Counter-based form of a keyed stream, for code that draws in vector lanes (RANSAC samples):
// word `counter` of the stream of `key` (any 64-bit value: it is mixed first, so keys 0, 1,
// 2, ... give unrelated streams). Each lane of a vector `counter` gets the word the scalar call
// gives for that lane's counter, so results do not depend on how draws are batched.
template <typename U32>
[[gnu::always_inline]] inline U32 CounterWord(uint64_t key, U32 counter) {
  const uint64_t mixed_key = MixBits(key ^ 0x6a09e667f3bcc909ULL);
  const U32 mixed = LowBias32<U32>(counter ^ static_cast<uint32_t>(mixed_key));
  return LowBias32<U32>(mixed + static_cast<uint32_t>(mixed_key >> 32));
}

// Standard normals out[0..count) for indices first .. first + count − 1 of the stream `key`:
// index i takes the counter words 2·⌊i/2⌋ and 2·⌊i/2⌋ + 1 as a uniform pair (24 bits each) and
// Box–Muller in float gives cos (even i) or sin (odd i), so each pair of words yields two normals.
// For per-pixel noise drawn a row at a time in vector lanes (Eigen's log/sin/cos); each value
// depends only on key and i, never on how a range is split (first may be odd).
void KeyedNormals(uint64_t key, int64_t first, int count, float* out);

// PCG32 (O'Neill 2014): small state, good statistics, cheap to construct per key.
class Rng {
 public:
  explicit Rng(uint64_t key) : state_(0), inc_((MixBits(key ^ 0xda3e39cb94b95bdbULL) << 1u) | 1u) {
    NextU32();
    state_ += MixBits(key);
    NextU32();
  }
  uint32_t NextU32() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ULL + inc_;
    const uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const uint32_t rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }
  // Uniform in [0, 1) with 53 bits.
  double Uniform() {
    const uint64_t hi = NextU32(), lo = NextU32();
    return static_cast<double>(((hi << 32) | lo) >> 11) * (1.0 / 9007199254740992.0);
  }
  // Uniform integer in [0, n) without modulo bias (Lemire).
  uint32_t UniformInt(uint32_t n) {
    uint64_t m = static_cast<uint64_t>(NextU32()) * n;
    uint32_t l = static_cast<uint32_t>(m);
    if (l < n) {
      const uint32_t t = (0u - n) % n;
      while (l < t) {
        m = static_cast<uint64_t>(NextU32()) * n;
        l = static_cast<uint32_t>(m);
      }
    }
    return static_cast<uint32_t>(m >> 32);
  }
  // Uniform in [lo, hi).
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
  // Uniform in [0, 1) with 24 bits, one draw: for hot loops (sensor noise).
  float UniformFloat() { return static_cast<float>(NextU32() >> 8) * (1.0f / 16777216.0f); }
  // Standard normal (Box–Muller, one value per call for simplicity of keying).
  double Normal() {
    const double u1 = 1.0 - Uniform();
    const double u2 = Uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }
  double Normal(double mean, double stddev) { return mean + stddev * Normal(); }

 private:
  uint64_t state_;
  uint64_t inc_;
};

// The stream for (seed, purpose, keys...): e.g. KeyedRng(seed, "sensor.netd", frame, pixel).
template <typename... Keys>
Rng KeyedRng(uint64_t seed, std::string_view purpose, Keys... keys) {
  return Rng(HashCombine(seed, HashString(purpose), static_cast<uint64_t>(keys)...));
}

}  // namespace hoilcd
