#include "hoilcd/core/estimators/homography_ransac.h"

// The 256-bit vector helpers are always inlined into their AVX2 / default clones, so no vector
// crosses a call boundary whose ABI could differ between the clones.
#pragma GCC diagnostic ignored "-Wpsabi"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/random.h"

namespace hoilcd {
namespace {

// A sample triplet whose angle sine at any vertex is below this is treated as collinear.
constexpr double kMinSampleSine = 1e-3;
// With redraw_degenerate_samples, at most trials * this many samples are drawn in all.
constexpr int64_t kMaxDrawsPerTrial = 10;
// Upper bound on RansacOptions::trials: the sample counters (4 per draw) stay below 2^32.
constexpr int kMaxTrials = 10'000'000;

// Signed doubled areas of the point triplets (0,1,2), (0,1,3), (0,2,3), (1,2,3) of a sample.
// With a, b, c = p1, p2, p3 minus p0, the area of (1,2,3) is b×c + a×b - a×c.
template <typename Real>
[[gnu::always_inline]] inline void TripletAreas(const Real x[4], const Real y[4], Real area[4]) {
  const Real ax = x[1] - x[0], ay = y[1] - y[0];
  const Real bx = x[2] - x[0], by = y[2] - y[0];
  const Real cx = x[3] - x[0], cy = y[3] - y[0];
  area[0] = ax * by - ay * bx;
  area[1] = ax * cy - ay * cx;
  area[2] = bx * cy - by * cx;
  area[3] = area[2] + area[0] - area[1];
}

// Eight float lanes (GCC vector extensions; the default clones lower them to two SSE halves).
using Floats8 = float __attribute__((vector_size(32)));
using Ints8 = int32_t __attribute__((vector_size(32)));

// The sample geometry below is written once for double (one sample) and Floats8 (eight samples,
// one per lane): comparisons give bool or a lane mask, and `?:` selects per lane.
template <typename Real>
struct ScalarOf {
  using Type = Real;
};
template <>
struct ScalarOf<Floats8> {
  using Type = float;
};

// *general = no triplet is (nearly) collinear: area² > sine² · |edge1|² · |edge2|² for the two
// edges at the triplet's first vertex.
template <typename Real, typename Mask>
[[gnu::always_inline]] inline void GeneralPosition(const Real x[4], const Real y[4], const Real area[4], Mask* general) {
  using Scalar = typename ScalarOf<Real>::Type;
  const Real ax = x[1] - x[0], ay = y[1] - y[0];
  const Real bx = x[2] - x[0], by = y[2] - y[0];
  const Real cx = x[3] - x[0], cy = y[3] - y[0];
  const Real ex = bx - ax, ey = by - ay, fx = cx - ax, fy = cy - ay;  // p2 - p1, p3 - p1
  const Real a2 = ax * ax + ay * ay, b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
  const Real e2 = ex * ex + ey * ey, f2 = fx * fx + fy * fy;
  const Scalar sine_sq = static_cast<Scalar>(kMinSampleSine * kMinSampleSine);
  *general = (area[0] * area[0] > sine_sq * (a2 * b2)) & (area[1] * area[1] > sine_sq * (a2 * c2)) &
             (area[2] * area[2] > sine_sq * (b2 * c2)) & (area[3] * area[3] > sine_sq * (e2 * f2));
}

// Unit square (0,0),(1,0),(1,1),(0,1) -> quad (x[i], y[i]) (Heckbert 1989), up to scale,
// row-major; division-free so a general-position quad gives a finite, non-singular matrix.
template <typename Real>
[[gnu::always_inline]] inline void SquareToQuad(const Real x[4], const Real y[4], Real m[9]) {
  const Real sx = x[0] - x[1] + x[2] - x[3];
  const Real sy = y[0] - y[1] + y[2] - y[3];
  const Real dx1 = x[1] - x[2], dx2 = x[3] - x[2];
  const Real dy1 = y[1] - y[2], dy2 = y[3] - y[2];
  const Real den = dx1 * dy2 - dx2 * dy1;
  const Real g = sx * dy2 - dx2 * sy;
  const Real h = dx1 * sy - sx * dy1;
  m[0] = (x[1] - x[0]) * den + g * x[1];
  m[1] = (x[3] - x[0]) * den + h * x[3];
  m[2] = x[0] * den;
  m[3] = (y[1] - y[0]) * den + g * y[1];
  m[4] = (y[3] - y[0]) * den + h * y[3];
  m[5] = y[0] * den;
  m[6] = g;
  m[7] = h;
  m[8] = den;
}

// Adjugate of a row-major 3x3 matrix (its inverse up to scale).
template <typename Real>
[[gnu::always_inline]] inline void Adjugate(const Real m[9], Real a[9]) {
  a[0] = m[4] * m[8] - m[5] * m[7];
  a[1] = m[2] * m[7] - m[1] * m[8];
  a[2] = m[1] * m[5] - m[2] * m[4];
  a[3] = m[5] * m[6] - m[3] * m[8];
  a[4] = m[0] * m[8] - m[2] * m[6];
  a[5] = m[2] * m[3] - m[0] * m[5];
  a[6] = m[3] * m[7] - m[4] * m[6];
  a[7] = m[1] * m[6] - m[0] * m[7];
  a[8] = m[0] * m[4] - m[1] * m[3];
}

template <typename Real>
[[gnu::always_inline]] inline void Multiply3(const Real a[9], const Real b[9], Real c[9]) {
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) {
      c[3 * r + k] = a[3 * r] * b[k] + a[3 * r + 1] * b[3 + k] + a[3 * r + 2] * b[6 + k];
    }
  }
}

// Closed-form 4-point homography src -> dst, up to scale. Each quad is moved to its centroid
// and scaled to coordinates within [-1, 1], which keeps the degree-9 polynomial entries in
// float range (relative precision is scale-invariant anyway).
template <typename Real>
[[gnu::always_inline]] inline void ClosedFormHomography(const Real sx[4], const Real sy[4], const Real dx[4],
                                 const Real dy[4], Real h[9]) {
  using Scalar = typename ScalarOf<Real>::Type;
  const Scalar quarter = 0.25f;
  const Real scx = quarter * (sx[0] + sx[1] + sx[2] + sx[3]);
  const Real scy = quarter * (sy[0] + sy[1] + sy[2] + sy[3]);
  const Real dcx = quarter * (dx[0] + dx[1] + dx[2] + dx[3]);
  const Real dcy = quarter * (dy[0] + dy[1] + dy[2] + dy[3]);
  // A quad of one repeated point keeps the smallest extent; GeneralPosition rejects it anyway.
  Real src_extent = std::numeric_limits<Scalar>::min() + scx * 0;
  Real dst_extent = src_extent;
  Real nsx[4], nsy[4], ndx[4], ndy[4];
  for (int i = 0; i < 4; ++i) {
    nsx[i] = sx[i] - scx;
    nsy[i] = sy[i] - scy;
    ndx[i] = dx[i] - dcx;
    ndy[i] = dy[i] - dcy;
    for (const Real& v : {nsx[i], nsy[i]}) {
      const Real magnitude = v < 0 ? -v : v;
      src_extent = magnitude > src_extent ? magnitude : src_extent;
    }
    for (const Real& v : {ndx[i], ndy[i]}) {
      const Real magnitude = v < 0 ? -v : v;
      dst_extent = magnitude > dst_extent ? magnitude : dst_extent;
    }
  }
  const Real src_scale = Scalar{1} / src_extent, dst_scale = Scalar{1} / dst_extent;
  for (int i = 0; i < 4; ++i) {
    nsx[i] *= src_scale;
    nsy[i] *= src_scale;
    ndx[i] *= dst_scale;
    ndy[i] *= dst_scale;
  }
  Real square_to_src[9], square_to_dst[9], src_to_square[9], hn[9];
  SquareToQuad(nsx, nsy, square_to_src);
  SquareToQuad(ndx, ndy, square_to_dst);
  Adjugate(square_to_src, src_to_square);
  Multiply3(square_to_dst, src_to_square, hn);
  // H = T(dst centroid) · S(dst_extent) · Hn · S(src_scale) · T(-src centroid).
  for (int r = 0; r < 3; ++r) {
    hn[3 * r] *= src_scale;
    hn[3 * r + 1] *= src_scale;
  }
  for (int k = 0; k < 6; ++k) hn[k] *= dst_extent;
  for (int r = 0; r < 3; ++r) hn[3 * r + 2] -= scx * hn[3 * r] + scy * hn[3 * r + 1];
  for (int k = 0; k < 3; ++k) {
    h[k] = hn[k] + dcx * hn[6 + k];
    h[3 + k] = hn[3 + k] + dcy * hn[6 + k];
    h[6 + k] = hn[6 + k];
  }
}

// Scales h so its largest entry has magnitude 1; false if h is zero or not finite.
inline bool NormaliseMaxAbs(double h[9]) {
  double largest = 0;
  for (int i = 0; i < 9; ++i) largest = std::max(largest, std::abs(h[i]));
  if (!(largest > 0) || !std::isfinite(largest)) return false;
  const double inv = 1.0 / largest;
  for (int i = 0; i < 9; ++i) h[i] *= inv;
  return true;
}

// Sampling. Draw d of a RANSAC call is four distinct match indices, uniform over ordered
// 4-tuples: digit k is uniform in [0, n - k) by Lemire's multiply-shift on the 32-bit word
// CounterWord(key, 4 d + k) with the exact rejection test, and is bumped past the k indices
// taken before it. A rejected word (probability below n / 2^32) is replaced by the same counter's
// word under the key MixBits(key + attempt). Counter-based, so eight draws run in vector lanes
// and give what one-by-one draws give (RansacSample is the scalar form, tested for uniformity).
struct DigitBounds {
  uint32_t range[4];      // n - k
  uint32_t reject_below[4];  // 2^32 mod (n - k): low words below this are rejected
  explicit DigitBounds(uint32_t n) {
    for (int k = 0; k < 4; ++k) {
      range[k] = n - static_cast<uint32_t>(k);
      reject_below[k] = (0u - range[k]) % range[k];
    }
  }
};

// Digit k of draw `draw`, one lane at a time (also the fix-up for rejected vector lanes).
uint32_t SampleDigit(uint64_t key, uint32_t draw, int k, const DigitBounds& bounds) {
  const uint32_t counter = 4 * draw + static_cast<uint32_t>(k);
  for (uint64_t attempt = 0;; ++attempt) {
    const uint64_t attempt_key = attempt == 0 ? key : MixBits(key + attempt);
    const uint64_t product = static_cast<uint64_t>(CounterWord(attempt_key, counter)) * bounds.range[k];
    if (static_cast<uint32_t>(product) >= bounds.reject_below[k]) {
      return static_cast<uint32_t>(product >> 32);
    }
  }
}

// Digits (digit[k] in [0, n - k)) to four distinct indices: each digit is bumped past every
// taken index at or below it, smallest taken first. Written once for uint32_t and Uints8.
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

// Eight samples of four match indices each: batch[k][b] is index k of sample b (vector lane b).
constexpr int kBatch = 8;
using SampleBatch = uint32_t[4][kBatch];
using Uints8 = uint32_t __attribute__((vector_size(32)));
using Uint64s4 = uint64_t __attribute__((vector_size(32)));
using Uints4 = uint32_t __attribute__((vector_size(16)));

// Draws first_draw .. first_draw + 7 into the lanes of *batch.
[[gnu::always_inline]] inline void DrawBatch(uint64_t key, uint32_t first_draw,
                                             const DigitBounds& bounds, SampleBatch* batch) {
  const Uints8 draw = Uints8{0, 1, 2, 3, 4, 5, 6, 7} + first_draw;
  Uints8 digit[4];
  Uints8 rejected = {};  // lanes with a rejected word in some digit
  for (int k = 0; k < 4; ++k) {
    const Uints8 word = CounterWord<Uints8>(key, 4 * draw + static_cast<uint32_t>(k));
    // 32 x 32 -> 64-bit products, four lanes at a time.
    const Uint64s4 low_half =
        __builtin_convertvector(__builtin_shufflevector(word, word, 0, 1, 2, 3), Uint64s4) *
        bounds.range[k];
    const Uint64s4 high_half =
        __builtin_convertvector(__builtin_shufflevector(word, word, 4, 5, 6, 7), Uint64s4) *
        bounds.range[k];
    const Uints4 digit_low = __builtin_convertvector(low_half >> 32, Uints4);
    const Uints4 digit_high = __builtin_convertvector(high_half >> 32, Uints4);
    const Uints4 rest_low = __builtin_convertvector(low_half, Uints4);
    const Uints4 rest_high = __builtin_convertvector(high_half, Uints4);
    digit[k] = __builtin_shufflevector(digit_low, digit_high, 0, 1, 2, 3, 4, 5, 6, 7);
    const Uints8 rest = __builtin_shufflevector(rest_low, rest_high, 0, 1, 2, 3, 4, 5, 6, 7);
    rejected |= rest < bounds.reject_below[k];
  }
  // Rejections are rare (probability below n / 2^32 per digit): one test for the whole batch.
  Uints8 folded = rejected | __builtin_shufflevector(rejected, rejected, 4, 5, 6, 7, 0, 1, 2, 3);
  folded |= __builtin_shufflevector(folded, folded, 2, 3, 0, 1, 6, 7, 4, 5);
  folded |= __builtin_shufflevector(folded, folded, 1, 0, 3, 2, 5, 4, 7, 6);
  if (__builtin_expect(folded[0] != 0, 0)) {
    for (int b = 0; b < kBatch; ++b) {
      if (!rejected[b]) continue;
      for (int k = 0; k < 4; ++k) digit[k][b] = SampleDigit(key, first_draw + b, k, bounds);
    }
  }
  Uints8 idx[4];
  DistinctFromDigits(digit, idx);
  std::memcpy(batch, idx, sizeof idx);
}

using Floats4 = float __attribute__((vector_size(16)));

// Gathers point k of every sample of a batch into lanes, from the matches as an array of
// (src x, src y, dst x, dst y) quadruples (src = reference, dst = query): one 16-byte load per
// point, then a 4x4 transpose within each 128-bit half. Built in registers: vector loads of
// scalar stores would stall on store forwarding.
[[gnu::always_inline]] inline void GatherPoints(const SampleBatch& batch, const float* quads,
                                                Floats8 sx[4], Floats8 sy[4], Floats8 dx[4],
                                                Floats8 dy[4]) {
  for (int k = 0; k < 4; ++k) {
    Floats8 rows[4];  // rows[j] = quadruple of sample j | quadruple of sample j + 4
    for (int j = 0; j < 4; ++j) {
      Floats4 low, high;
      std::memcpy(&low, quads + 4 * batch[k][j], sizeof low);
      std::memcpy(&high, quads + 4 * batch[k][j + 4], sizeof high);
      rows[j] = __builtin_shufflevector(low, high, 0, 1, 2, 3, 4, 5, 6, 7);
    }
    const Floats8 t0 = __builtin_shufflevector(rows[0], rows[1], 0, 8, 1, 9, 4, 12, 5, 13);
    const Floats8 t1 = __builtin_shufflevector(rows[2], rows[3], 0, 8, 1, 9, 4, 12, 5, 13);
    const Floats8 t2 = __builtin_shufflevector(rows[0], rows[1], 2, 10, 3, 11, 6, 14, 7, 15);
    const Floats8 t3 = __builtin_shufflevector(rows[2], rows[3], 2, 10, 3, 11, 6, 14, 7, 15);
    sx[k] = __builtin_shufflevector(t0, t1, 0, 1, 8, 9, 4, 5, 12, 13);
    sy[k] = __builtin_shufflevector(t0, t1, 2, 3, 10, 11, 6, 7, 14, 15);
    dx[k] = __builtin_shufflevector(t2, t3, 0, 1, 8, 9, 4, 5, 12, 13);
    dy[k] = __builtin_shufflevector(t2, t3, 2, 3, 10, 11, 6, 7, 14, 15);
  }
}

// The hypotheses of a SampleBatch.
struct HypothesisBatch {
  float h[9][kBatch];     // hypothesis of each lane, max |h| = 1
  int32_t valid[kBatch];  // 0 if the sample is degenerate
};

// consistent[b] = 0 if sample b keeps the orientation of some of its four point triplets but
// flips others: no homography without a point at infinity between the images does that
// (OpenCV's HomographyEstimatorCallback::checkSubset applies the same test). Most random
// samples fail it, so it runs on every draw and only the survivors are solved. Float is
// enough: a sign can only come out wrong for a nearly collinear triplet, rejected later anyway.
// Draws the batch first (draws first_draw .. first_draw + 7).
// Cloned for AVX2 with run-time dispatch; no FMA, so both clones give the same floats.
__attribute__((target_clones("avx2", "default"))) void DrawAndCheckOrientations(
    uint64_t key, uint32_t first_draw, const DigitBounds& bounds, const float* quads,
    SampleBatch* drawn, int32_t consistent[kBatch]) {
  DrawBatch(key, first_draw, bounds, drawn);
  const SampleBatch& batch = *drawn;
  Floats8 sx[4], sy[4], dx[4], dy[4];
  GatherPoints(batch, quads, sx, sy, dx, dy);
  Floats8 src_area[4], dst_area[4];
  TripletAreas(sx, sy, src_area);
  TripletAreas(dx, dy, dst_area);
  Floats8 products[4];
  for (int k = 0; k < 4; ++k) products[k] = src_area[k] * dst_area[k];
  const Ints8 result =
      ((products[0] < 0) & (products[1] < 0) & (products[2] < 0) & (products[3] < 0)) |
      ((products[0] >= 0) & (products[1] >= 0) & (products[2] >= 0) & (products[3] >= 0));
  std::memcpy(consistent, &result, sizeof result);
}

// Solves the eight samples of a batch in float, one per lane (cloned like CheckOrientations).
// A lane is invalid if three of its points are (nearly) collinear in either image or if its
// closed-form solution is zero or not finite.
__attribute__((target_clones("avx2", "default"))) void SolveBatch(const SampleBatch& batch,
                                                                   const float* quads,
                                                                   HypothesisBatch* out) {
  Floats8 sx[4], sy[4], dx[4], dy[4];
  GatherPoints(batch, quads, sx, sy, dx, dy);
  Floats8 src_area[4], dst_area[4];
  TripletAreas(sx, sy, src_area);
  TripletAreas(dx, dy, dst_area);
  Ints8 src_general, dst_general;
  GeneralPosition(sx, sy, src_area, &src_general);
  GeneralPosition(dx, dy, dst_area, &dst_general);
  Floats8 h[9];
  ClosedFormHomography(sx, sy, dx, dy, h);
  Floats8 largest = {};
  for (int i = 0; i < 9; ++i) {
    const Floats8 magnitude = h[i] < 0 ? -h[i] : h[i];
    largest = magnitude > largest ? magnitude : largest;
  }
  const Ints8 finite = (largest > 0) & (largest <= std::numeric_limits<float>::max());
  const Floats8 one = {1, 1, 1, 1, 1, 1, 1, 1};
  const Floats8 inv = 1.0f / (finite ? largest : one);
  for (int i = 0; i < 9; ++i) h[i] *= inv;
  std::memcpy(out->h, h, sizeof h);
  const Ints8 valid = src_general & dst_general & finite;
  std::memcpy(out->valid, &valid, sizeof valid);
}

[[gnu::always_inline]] inline int32_t HorizontalSum(const Ints8& v) {
  Ints8 sum = v + __builtin_shufflevector(v, v, 4, 5, 6, 7, 0, 1, 2, 3);
  sum += __builtin_shufflevector(sum, sum, 2, 3, 0, 1, 6, 7, 4, 5);
  sum += __builtin_shufflevector(sum, sum, 1, 0, 3, 2, 5, 4, 7, 6);
  return sum[0];
}

// Adds to *negative_count, lane by lane, minus one for each of the eight matches from `start`
// that is an inlier of h and whose lane is set in `keep`. Division-free:
// |(u, v) / w - q| < t  <=>  |(u, v) - q w|² < t² w²  (false when w = 0).
[[gnu::always_inline]] inline void CountEight(const Floats8 h[9], const float* ref_x,
                                              const float* ref_y, const float* query_x,
                                              const float* query_y, int start,
                                              const Floats8& threshold_sq, const Ints8& keep,
                                              Ints8* negative_count) {
  Floats8 x, y, qx, qy;
  std::memcpy(&x, ref_x + start, sizeof x);
  std::memcpy(&y, ref_y + start, sizeof y);
  std::memcpy(&qx, query_x + start, sizeof qx);
  std::memcpy(&qy, query_y + start, sizeof qy);
  const Floats8 w = h[6] * x + h[7] * y + h[8];
  const Floats8 du = h[0] * x + h[1] * y + h[2] - qx * w;
  const Floats8 dv = h[3] * x + h[4] * y + h[5] - qy * w;
  *negative_count += (du * du + dv * dv < threshold_sq * (w * w)) & keep;
}

// Inlier count of h over all matches, or some count <= bar once it cannot exceed bar (which
// leaves the result of the RANSAC loop unchanged). Eight matches per step; for a count that is
// not a multiple of 8 the last step reloads the final eight and masks those already counted.
__attribute__((target_clones("avx2", "default"))) int CountInliers(
    const float h[9], const float* ref_x, const float* ref_y, const float* query_x,
    const float* query_y, int count, float threshold_sq, int bar) {
  if (count < 8) {
    int inliers = 0;
    for (int i = 0; i < count; ++i) {
      const float x = ref_x[i], y = ref_y[i];
      const float w = h[6] * x + h[7] * y + h[8];
      const float du = h[0] * x + h[1] * y + h[2] - query_x[i] * w;
      const float dv = h[3] * x + h[4] * y + h[5] - query_y[i] * w;
      inliers += (du * du + dv * dv < threshold_sq * (w * w)) ? 1 : 0;
    }
    return inliers;
  }
  Floats8 hv[9];
  for (int k = 0; k < 9; ++k) hv[k] = Floats8{} + h[k];
  const Floats8 threshold = Floats8{} + threshold_sq;
  const Ints8 all = {-1, -1, -1, -1, -1, -1, -1, -1};
  Ints8 negative_count = {};
  const int whole = count - count % 8;
  // The count cannot fall to the bar before count - bar matches are seen: no check until then,
  // then a check after every step.
  const int first_check = count - bar;
  int i = 0;
  for (; i < whole && i + 8 < first_check; i += 8) {
    CountEight(hv, ref_x, ref_y, query_x, query_y, i, threshold, all, &negative_count);
  }
  for (; i < whole; i += 8) {
    CountEight(hv, ref_x, ref_y, query_x, query_y, i, threshold, all, &negative_count);
    const int inliers = -HorizontalSum(negative_count);
    if (inliers + (count - i - 8) <= bar) return inliers;
  }
  if (whole < count) {
    const Ints8 lane = {0, 1, 2, 3, 4, 5, 6, 7};
    CountEight(hv, ref_x, ref_y, query_x, query_y, count - 8, threshold,
               lane >= 8 - count % 8, &negative_count);
  }
  return -HorizontalSum(negative_count);
}

void MarkInliers(const float h[9], const float* ref_x, const float* ref_y, const float* query_x,
                 const float* query_y, int count, float threshold_sq, uint8_t* mask) {
  for (int i = 0; i < count; ++i) {
    const float x = ref_x[i], y = ref_y[i];
    const float w = h[6] * x + h[7] * y + h[8];
    const float du = h[0] * x + h[1] * y + h[2] - query_x[i] * w;
    const float dv = h[3] * x + h[4] * y + h[5] - query_y[i] * w;
    mask[i] = (du * du + dv * dv < threshold_sq * (w * w)) ? 1 : 0;
  }
}

// Similarity normalisation x' = s (x - c) of a point set.
struct Normalisation {
  double cx, cy, scale;
};

// H = T_dst⁻¹ · Hn · T_src for similarity normalisations T (x' = s (x - c)).
void Denormalise(const double hn[9], const Normalisation& src, const Normalisation& dst,
                 double h[9]) {
  double t[9];
  for (int r = 0; r < 3; ++r) {
    t[3 * r] = hn[3 * r] * src.scale;
    t[3 * r + 1] = hn[3 * r + 1] * src.scale;
    t[3 * r + 2] = hn[3 * r + 2] - src.scale * (src.cx * hn[3 * r] + src.cy * hn[3 * r + 1]);
  }
  const double inv = 1.0 / dst.scale;
  for (int k = 0; k < 3; ++k) {
    h[k] = t[k] * inv + dst.cx * t[6 + k];
    h[3 + k] = t[3 + k] * inv + dst.cy * t[6 + k];
    h[6 + k] = t[6 + k];
  }
}

template <typename Real>
Eigen::Matrix3d ToResultMatrix(const Real h[9]) {
  Eigen::Matrix3d m;
  m << h[0], h[1], h[2], h[3], h[4], h[5], h[6], h[7], h[8];
  if (std::abs(m(2, 2)) > 1e-12 * m.cwiseAbs().maxCoeff()) m /= m(2, 2);
  return m;
}

}  // namespace

RansacOptions::RansacOptions() { Table().FillDefaults(this); }

const OptionTable<RansacOptions>& RansacOptions::Table() {
  using O = RansacOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("trials", &O::trials, 100, "", R::Closed(1, kMaxTrials), "RANSAC hypotheses per pair (paper: 100)")
          .Add("redraw_degenerate_samples", &O::redraw_degenerate_samples, true,
               "a degenerate sample is redrawn (up to 10 draws per trial on average) instead of using up its trial")
          .Add("inlier_threshold_px", &O::inlier_threshold_px, 5.0, "px", R::Any().Above(0),
               "reprojection error bound of an inlier")
          // Each refit is a least-squares solve per better hypothesis; LO-RANSAC uses a few.
          .Add("local_optimisation_refits", &O::local_optimisation_refits, 0, "", R::Closed(0, 100),
               "LO-RANSAC least-squares refits on the inliers of each new best model (0: plain RANSAC, the paper's)");
  return table;
}

std::string RansacOptions::Check() const { return Table().FirstProblem(*this); }

void RansacSample(uint64_t seed, uint32_t draw, uint32_t n, uint32_t idx[4]) {
  HOILCD_CHECK_MSG(n >= 4, "a sample needs n >= 4 matches (got " << n << ")");
  const DigitBounds bounds(n);
  uint32_t digit[4];
  for (int k = 0; k < 4; ++k) digit[k] = SampleDigit(seed, draw, k, bounds);
  DistinctFromDigits(digit, idx);
}

bool HomographyFromFourPoints(const Point2 src[4], const Point2 dst[4], Eigen::Matrix3d* h) {
  HOILCD_CHECK(h != nullptr);
  double sx[4], sy[4], dx[4], dy[4], m[9];
  for (int i = 0; i < 4; ++i) {
    sx[i] = src[i].x;
    sy[i] = src[i].y;
    dx[i] = dst[i].x;
    dy[i] = dst[i].y;
  }
  double src_area[4], dst_area[4];
  TripletAreas(sx, sy, src_area);
  TripletAreas(dx, dy, dst_area);
  bool src_general = false, dst_general = false;
  GeneralPosition(sx, sy, src_area, &src_general);
  GeneralPosition(dx, dy, dst_area, &dst_general);
  if (!src_general || !dst_general) return false;
  ClosedFormHomography(sx, sy, dx, dy, m);
  if (!NormaliseMaxAbs(m)) return false;
  *h = ToResultMatrix(m);
  return true;
}

bool HomographyLeastSquares(const float* ref_x, const float* ref_y, const float* query_x,
                            const float* query_y, const uint8_t* use, int count,
                            Eigen::Matrix3d* h) {
  HOILCD_CHECK(h != nullptr);
  // Hartley normalisation: centroid to the origin, mean distance sqrt(2).
  double rcx = 0, rcy = 0, qcx = 0, qcy = 0;
  int n = 0;
  for (int i = 0; i < count; ++i) {
    if (use != nullptr && !use[i]) continue;
    rcx += ref_x[i];
    rcy += ref_y[i];
    qcx += query_x[i];
    qcy += query_y[i];
    ++n;
  }
  if (n < 4) return false;
  rcx /= n;
  rcy /= n;
  qcx /= n;
  qcy /= n;
  double rd = 0, qd = 0;
  for (int i = 0; i < count; ++i) {
    if (use != nullptr && !use[i]) continue;
    // Not std::hypot: pixel offsets cannot overflow, and its care costs 5 % of a bench's RANSAC.
    const double rx = ref_x[i] - rcx, ry = ref_y[i] - rcy, qx = query_x[i] - qcx, qy = query_y[i] - qcy;
    rd += std::sqrt(rx * rx + ry * ry);
    qd += std::sqrt(qx * qx + qy * qy);
  }
  if (!(rd > 0) || !(qd > 0)) return false;
  const Normalisation src{rcx, rcy, std::sqrt(2.0) * n / rd};
  const Normalisation dst{qcx, qcy, std::sqrt(2.0) * n / qd};
  // AᵀA of the DLT rows [-p, 0, u p] and [0, -p, v p] (p = (x, y, 1)) is made of the moment
  // matrices S = Σ p pᵀ, U = Σ u p pᵀ, V = Σ v p pᵀ and W = Σ (u² + v²) p pᵀ.
  Eigen::Matrix3d s_sum = Eigen::Matrix3d::Zero(), u_sum = s_sum, v_sum = s_sum, w_sum = s_sum;
  for (int i = 0; i < count; ++i) {
    if (use != nullptr && !use[i]) continue;
    const double x = (ref_x[i] - src.cx) * src.scale, y = (ref_y[i] - src.cy) * src.scale;
    const double u = (query_x[i] - dst.cx) * dst.scale, v = (query_y[i] - dst.cy) * dst.scale;
    const Eigen::Vector3d p(x, y, 1.0);
    const Eigen::Matrix3d ppt = p * p.transpose();
    s_sum += ppt;
    u_sum += u * ppt;
    v_sum += v * ppt;
    w_sum += (u * u + v * v) * ppt;
  }
  Eigen::Matrix<double, 9, 9> ata = Eigen::Matrix<double, 9, 9>::Zero();
  ata.block<3, 3>(0, 0) = s_sum;
  ata.block<3, 3>(3, 3) = s_sum;
  ata.block<3, 3>(0, 6) = -u_sum;
  ata.block<3, 3>(6, 0) = -u_sum;
  ata.block<3, 3>(3, 6) = -v_sum;
  ata.block<3, 3>(6, 3) = -v_sum;
  ata.block<3, 3>(6, 6) = w_sum;
  // Fixing h(2,2) = 1 turns min hᵀ AᵀA h into the 8x8 normal equations M h' = -c; in normalised
  // coordinates h(2,2) stays away from 0 for any homography that keeps the centroid finite.
  const Eigen::LDLT<Eigen::Matrix<double, 8, 8>> ldlt(ata.topLeftCorner<8, 8>());
  if (ldlt.info() != Eigen::Success) return false;
  Eigen::Matrix<double, 9, 1> null_vector;
  null_vector.head<8>() = ldlt.solve(-ata.block<8, 1>(0, 8));
  null_vector(8) = 1.0;
  if (!null_vector.allFinite()) return false;
  double hn[9], m[9];
  for (int i = 0; i < 9; ++i) hn[i] = null_vector(i);
  Denormalise(hn, src, dst, m);
  if (!NormaliseMaxAbs(m)) return false;
  Eigen::Matrix3d result;
  result << m[0], m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8];
  if (std::abs(result.determinant()) < 1e-12) return false;
  *h = ToResultMatrix(m);
  return true;
}

namespace {

// Hypotheses kept between drawing and scoring. Small, so that a search that is complete (every
// match an inlier) stops drawing soon: 16 saved ~7 % of the point-set methods' CPU over 128.
constexpr int kChunk = 16;
static_assert(kChunk >= kBatch, "HypothesisStream::Next needs room for a solved batch");

// Matches as (reference x, reference y, query x, query y) quadruples, the layout GatherPoints
// reads; *quads is resized to 4 * count.
void Quadruples(const float* ref_x, const float* ref_y, const float* query_x, const float* query_y, int count,
                std::vector<float>* quads) {
  quads->resize(4 * static_cast<size_t>(count));
  for (int i = 0; i < count; ++i) {
    (*quads)[4 * i] = ref_x[i];
    (*quads)[4 * i + 1] = ref_y[i];
    (*quads)[4 * i + 2] = query_x[i];
    (*quads)[4 * i + 3] = query_y[i];
  }
}

// The hypotheses of one RANSAC stream, in draw order: samples are drawn eight at a time, those
// with consistent orientations are queued in draw order and solved eight at a time, and each
// non-degenerate solution is a hypothesis, up to options.trials of them. The stream depends only
// on the matches, the seed, trials and redraw_degenerate_samples: variants that differ only in
// their threshold or refits score the same hypotheses.
class HypothesisStream {
 public:
  HypothesisStream(const float* quads, int count, const RansacOptions& options, uint64_t seed)
      : quads_(quads),
        bounds_(static_cast<uint32_t>(count)),
        seed_(seed),
        trials_(options.trials),
        // With exactly 4 matches every sample is the same set: one draw decides.
        budget_(count == 4 ? 1
                           : static_cast<int64_t>(options.trials) *
                                 (options.redraw_degenerate_samples ? kMaxDrawsPerTrial : 1)) {}

  // Writes the next hypotheses to out (9 floats each, max |h| = 1), at most max >= kBatch of
  // them, and returns how many.
  int Next(int max, float* out) {
    int n = 0;
    while (n + kBatch <= max && !Done()) {
      if (draws_ >= budget_) {  // the last, partly filled queue
        n += Solve(queued_, out + 9 * n);
        queued_ = 0;
        break;
      }
      const int size = static_cast<int>(std::min<int64_t>(kBatch, budget_ - draws_));
      SampleBatch drawn;
      int32_t consistent[kBatch];
      DrawAndCheckOrientations(seed_, static_cast<uint32_t>(draws_), bounds_, quads_, &drawn, consistent);
      draws_ += size;
      for (int b = 0; b < size; ++b) {
        // Branch-free queueing: every sample is copied, only consistent ones advance the queue.
        for (int k = 0; k < 4; ++k) pending_[k][queued_] = drawn[k][b];
        queued_ -= consistent[b];  // a consistent lane holds -1
        if (queued_ == kBatch) {   // at most once per drawn batch, so n stays within max
          n += Solve(kBatch, out + 9 * n);
          queued_ = 0;
        }
      }
    }
    return n;
  }

  // No hypothesis is left: trials are in, or every draw is spent and solved.
  bool Done() const { return produced_ >= trials_ || (draws_ >= budget_ && queued_ == 0); }

 private:
  // Solves the first `size` queued samples; writes the valid ones, up to the trials left.
  int Solve(int size, float* out) {
    HypothesisBatch solved;
    SolveBatch(pending_, quads_, &solved);
    int n = 0;
    for (int b = 0; b < size && produced_ < trials_; ++b) {
      if (!solved.valid[b]) continue;
      for (int k = 0; k < 9; ++k) out[9 * n + k] = solved.h[k][b];
      ++n;
      ++produced_;
    }
    return n;
  }

  const float* quads_;
  DigitBounds bounds_;
  uint64_t seed_;
  int trials_;
  int64_t budget_;
  int64_t draws_ = 0;
  int produced_ = 0;
  SampleBatch pending_ = {};  // unused lanes keep index 0, a valid match
  int queued_ = 0;
};

// One variant's search over a stream: the best model so far and its inlier count, with the
// LO-RANSAC refits of each new best model. lo_mask is scratch (kept between calls by its owner).
class BestModelSearch {
 public:
  void Start(const float* ref_x, const float* ref_y, const float* query_x, const float* query_y, int count,
             const RansacOptions& options, std::vector<uint8_t>* lo_mask) {
    ref_x_ = ref_x, ref_y_ = ref_y, query_x_ = query_x, query_y_ = query_y, count_ = count;
    threshold_sq_ = static_cast<float>(options.inlier_threshold_px * options.inlier_threshold_px);
    refits_ = options.local_optimisation_refits;
    lo_mask_ = lo_mask;
    const float identity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    std::copy(identity, identity + 9, best_);
    best_inliers_ = 0;
  }

  // Scores n hypotheses (9 floats each) in order, up to the first that makes the search complete.
  void Score(const float* hypotheses, int n) {
    for (int i = 0; i < n && !Complete(); ++i) {
      float hf[9];
      std::copy(hypotheses + 9 * i, hypotheses + 9 * i + 9, hf);
      const int inliers = CountInliers(hf, ref_x_, ref_y_, query_x_, query_y_, count_, threshold_sq_, best_inliers_);
      if (inliers <= best_inliers_) continue;
      best_inliers_ = inliers;
      std::copy(hf, hf + 9, best_);
      if (refits_ <= 0 || inliers <= 4) continue;
      lo_mask_->resize(count_);
      MarkInliers(hf, ref_x_, ref_y_, query_x_, query_y_, count_, threshold_sq_, lo_mask_->data());
      for (int refit = 0; refit < refits_; ++refit) {
        Eigen::Matrix3d fit;
        if (!HomographyLeastSquares(ref_x_, ref_y_, query_x_, query_y_, lo_mask_->data(), count_, &fit)) break;
        double hr[9];
        for (int k = 0; k < 9; ++k) hr[k] = fit(k / 3, k % 3);
        if (!NormaliseMaxAbs(hr)) break;
        for (int k = 0; k < 9; ++k) hf[k] = static_cast<float>(hr[k]);
        const int refit_inliers =
            CountInliers(hf, ref_x_, ref_y_, query_x_, query_y_, count_, threshold_sq_, best_inliers_);
        if (refit_inliers <= best_inliers_) break;
        best_inliers_ = refit_inliers;
        std::copy(hf, hf + 9, best_);
        MarkInliers(hf, ref_x_, ref_y_, query_x_, query_y_, count_, threshold_sq_, lo_mask_->data());
      }
    }
  }

  int inliers() const { return best_inliers_; }
  // Every match is an inlier of the best model: no later hypothesis or refit can beat it (a new
  // best needs strictly more inliers), so the rest of the stream cannot change the result.
  bool Complete() const { return best_inliers_ >= count_; }
  const float* best() const { return best_; }
  float threshold_sq() const { return threshold_sq_; }

 private:
  const float *ref_x_ = nullptr, *ref_y_ = nullptr, *query_x_ = nullptr, *query_y_ = nullptr;
  int count_ = 0;
  float threshold_sq_ = 0;
  int refits_ = 0;
  std::vector<uint8_t>* lo_mask_ = nullptr;
  float best_[9] = {};
  int best_inliers_ = 0;
};

// Variants score one stream when they draw the same samples.
bool SameStream(const RansacOptions& a, const RansacOptions& b) {
  return a.trials == b.trials && a.redraw_degenerate_samples == b.redraw_degenerate_samples;
}

}  // namespace

// Hand-written rather than cv::findHomography: the paper runs exactly N trials, while OpenCV
// stops adaptively and refines the model afterwards.
int RansacHomographySoa(const float* ref_x, const float* ref_y, const float* query_x,
                        const float* query_y, int count, const RansacOptions& options,
                        uint64_t seed, Eigen::Matrix3d* best_h, uint8_t* inlier_mask) {
  if (count < 4) {
    if (best_h != nullptr) best_h->setIdentity();
    if (inlier_mask != nullptr) std::fill(inlier_mask, inlier_mask + count, uint8_t{0});
    return 0;
  }
  std::vector<float> quads;
  Quadruples(ref_x, ref_y, query_x, query_y, count, &quads);
  HypothesisStream stream(quads.data(), count, options, seed);
  std::vector<uint8_t> lo_mask;
  BestModelSearch search;
  search.Start(ref_x, ref_y, query_x, query_y, count, options, &lo_mask);
  float hypotheses[9 * kChunk];
  while (!stream.Done() && !search.Complete()) {
    const int n = stream.Next(kChunk, hypotheses);
    search.Score(hypotheses, n);
  }
  if (best_h != nullptr) *best_h = ToResultMatrix(search.best());
  if (inlier_mask != nullptr) {
    if (search.inliers() == 0) {
      std::fill(inlier_mask, inlier_mask + count, uint8_t{0});
    } else {
      MarkInliers(search.best(), ref_x, ref_y, query_x, query_y, count, search.threshold_sq(), inlier_mask);
    }
  }
  return search.inliers();
}

void RansacCounter::Count(const float* ref_x, const float* ref_y, const float* query_x, const float* query_y,
                          int count, const RansacOptions* variants, int num_variants, uint64_t seed, int* inliers,
                          int64_t* alone_ns, int64_t* total_ns) {
  const bool timed = alone_ns != nullptr;
  HOILCD_CHECK_MSG(!timed || total_ns != nullptr, "alone_ns needs total_ns");
  hypotheses_scored_ = 0;
  if (timed) {
    std::fill(alone_ns, alone_ns + num_variants, int64_t{0});
    *total_ns = 0;
  }
  if (count < 4) {
    std::fill(inliers, inliers + num_variants, 0);
    return;
  }
  using Clock = std::chrono::steady_clock;
  const auto elapsed_ns = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(b - a).count();
  };
  const Clock::time_point start = timed ? Clock::now() : Clock::time_point();
  Clock::time_point last = start;  // the gathering below counts as the first stream's drawing
  Quadruples(ref_x, ref_y, query_x, query_y, count, &quads_);
  if (lo_masks_.size() < static_cast<size_t>(num_variants)) lo_masks_.resize(num_variants);
  scored_.assign(num_variants, 0);  // 1 once a variant is in a group
  hypotheses_.resize(9 * kChunk);
  // Groups of variants on one stream, in order: the first variant not yet scored and every later
  // one on the same stream, at most kMaxSharing at once (a larger group draws its stream again).
  constexpr int kMaxSharing = 8;
  for (int first = 0; first < num_variants; ++first) {
    if (scored_[first]) continue;
    int group[kMaxSharing], size = 0;
    BestModelSearch searches[kMaxSharing];
    for (int v = first; v < num_variants && size < kMaxSharing; ++v) {
      if (scored_[v] || !SameStream(variants[first], variants[v])) continue;
      scored_[v] = 1;
      searches[size].Start(ref_x, ref_y, query_x, query_y, count, variants[v], &lo_masks_[v]);
      group[size++] = v;
    }
    HypothesisStream stream(quads_.data(), count, variants[first], seed);
    const auto complete = [&] {
      return std::all_of(searches, searches + size, [](const BestModelSearch& s) { return s.Complete(); });
    };
    while (!stream.Done() && !complete()) {
      const int n = stream.Next(kChunk, hypotheses_.data());
      hypotheses_scored_ += n;
      Clock::time_point now;
      int64_t drawing_ns = 0;
      if (timed) {
        now = Clock::now();
        drawing_ns = elapsed_ns(last, now);
        last = now;
      }
      for (int g = 0; g < size; ++g) {
        searches[g].Score(hypotheses_.data(), n);
        if (!timed) continue;
        now = Clock::now();
        alone_ns[group[g]] += drawing_ns + elapsed_ns(last, now);
        last = now;
      }
    }
    for (int g = 0; g < size; ++g) inliers[group[g]] = searches[g].inliers();
  }
  if (timed) *total_ns = elapsed_ns(start, last);
}

namespace {

// Checks the options, gathers the matched coordinates as structure of arrays and runs
// RansacHomographySoa on them (best_h and inlier_mask as there).
int RansacOnMatches(const std::vector<Point2>& query, const std::vector<Point2>& reference,
                    const std::vector<Correspondence>& matches, const RansacOptions& options, uint64_t seed,
                    Eigen::Matrix3d* best_h, uint8_t* inlier_mask) {
  const std::string problem = options.Check();
  HOILCD_CHECK_MSG(problem.empty(), problem);
  const int count = static_cast<int>(matches.size());
  std::vector<float> xy(4 * static_cast<size_t>(count));  // reference x, reference y, query x, query y
  for (int i = 0; i < count; ++i) {
    const Correspondence& m = matches[i];
    HOILCD_CHECK_MSG(m.query >= 0 && m.query < static_cast<int>(query.size()) &&
                         m.reference >= 0 && m.reference < static_cast<int>(reference.size()),
                     "match " << i << " (" << m.query << ", " << m.reference
                              << ") is out of range");
    xy[i] = reference[m.reference].x;
    xy[count + i] = reference[m.reference].y;
    xy[2 * count + i] = query[m.query].x;
    xy[3 * count + i] = query[m.query].y;
  }
  return RansacHomographySoa(xy.data(), xy.data() + count, xy.data() + 2 * count, xy.data() + 3 * count, count,
                             options, seed, best_h, inlier_mask);
}

}  // namespace

HomographyResult EstimateHomographyRansac(const std::vector<Point2>& query,
                                          const std::vector<Point2>& reference,
                                          const std::vector<Correspondence>& matches,
                                          const RansacOptions& options, uint64_t seed) {
  HomographyResult result;
  result.inlier_mask.resize(matches.size());
  result.inliers = RansacOnMatches(query, reference, matches, options, seed, &result.reference_to_query,
                                   result.inlier_mask.data());
  return result;
}

int CountRansacInliers(const std::vector<Point2>& query, const std::vector<Point2>& reference,
                       const std::vector<Correspondence>& matches, const RansacOptions& options, uint64_t seed) {
  return RansacOnMatches(query, reference, matches, options, seed, nullptr, nullptr);
}

}  // namespace hoilcd
