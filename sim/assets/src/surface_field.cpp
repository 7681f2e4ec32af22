#include "hoilcd/sim/assets/surface_field.h"

#include <cmath>

#include "hoilcd/core/util/random.h"

namespace hoilcd {

namespace {

// Lattice value in [−1, 1] at integer cell (x, y, z) of the pattern `key`.
float Lattice(uint64_t key, int x, int y, int z) {
  const uint64_t h = HashCombine(key, static_cast<uint32_t>(x), static_cast<uint32_t>(y), static_cast<uint32_t>(z));
  return static_cast<float>(h >> 40) * (2.0f / 16777216.0f) - 1.0f;
}

float Fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }

}  // namespace

float ValueNoise3(uint64_t key, const Eigen::Vector3f& point) {
  const float fx = std::floor(point.x()), fy = std::floor(point.y()), fz = std::floor(point.z());
  const int x = static_cast<int>(fx), y = static_cast<int>(fy), z = static_cast<int>(fz);
  const float u = Fade(point.x() - fx), v = Fade(point.y() - fy), w = Fade(point.z() - fz);
  auto lerp = [](float a, float b, float t) { return a + t * (b - a); };
  const float x00 = lerp(Lattice(key, x, y, z), Lattice(key, x + 1, y, z), u);
  const float x10 = lerp(Lattice(key, x, y + 1, z), Lattice(key, x + 1, y + 1, z), u);
  const float x01 = lerp(Lattice(key, x, y, z + 1), Lattice(key, x + 1, y, z + 1), u);
  const float x11 = lerp(Lattice(key, x, y + 1, z + 1), Lattice(key, x + 1, y + 1, z + 1), u);
  return lerp(lerp(x00, x10, v), lerp(x01, x11, v), w);
}

}  // namespace hoilcd
