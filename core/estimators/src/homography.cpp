// The 256-bit vector helpers are always inlined into their AVX2 / default clones, so no vector
// crosses a call boundary whose ABI could differ between the clones. Before the includes: GCC
// places its note at the helpers' declarations (random.h's CounterWord among them).
#pragma GCC diagnostic ignored "-Wpsabi"

#include "hoilcd/core/estimators/homography.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "hoilcd/core/util/error.h"

namespace hoilcd {
namespace {

// A sample triplet whose angle sine at any vertex is below this is treated as collinear.
constexpr double kMinSampleSine = 1e-3;

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
[[gnu::always_inline]] inline void GeneralPosition(const Real x[4], const Real y[4], const Real area[4],
                                                   Mask* general) {
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

using Floats4 = float __attribute__((vector_size(16)));

// Gathers point k of every sample of a batch into lanes, from the matches as an array of
// (src x, src y, dst x, dst y) quadruples (src = reference, dst = query): one 16-byte load per
// point, then a 4x4 transpose within each 128-bit half. Built in registers: vector loads of
// scalar stores would stall on store forwarding.
[[gnu::always_inline]] inline void GatherPoints(const SampleBatch& batch, const float* quads, Floats8 sx[4],
                                                Floats8 sy[4], Floats8 dx[4], Floats8 dy[4]) {
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

[[gnu::always_inline]] inline int32_t HorizontalSum(const Ints8& v) {
  Ints8 sum = v + __builtin_shufflevector(v, v, 4, 5, 6, 7, 0, 1, 2, 3);
  sum += __builtin_shufflevector(sum, sum, 2, 3, 0, 1, 6, 7, 4, 5);
  sum += __builtin_shufflevector(sum, sum, 1, 0, 3, 2, 5, 4, 7, 6);
  return sum[0];
}

// Adds to *negative_count, lane by lane, minus one for each of the eight matches from `start`
// that is an inlier of h and whose lane is set in `keep`. Division-free:
// |(u, v) / w - q| < t  <=>  |(u, v) - q w|² < t² w²  (false when w = 0).
[[gnu::always_inline]] inline void CountEight(const Floats8 h[9], const float* ref_x, const float* ref_y,
                                              const float* query_x, const float* query_y, int start,
                                              const Floats8& threshold_sq, const Ints8& keep, Ints8* negative_count) {
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

// Similarity normalisation x' = s (x - c) of a point set.
struct Normalisation {
  double cx, cy, scale;
};

// H = T_dst⁻¹ · Hn · T_src for similarity normalisations T (x' = s (x - c)).
void Denormalise(const double hn[9], const Normalisation& src, const Normalisation& dst, double h[9]) {
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

bool HomographyLeastSquares(const float* ref_x, const float* ref_y, const float* query_x, const float* query_y,
                            const uint8_t* use, int count, Eigen::Matrix3d* h) {
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

HomographyEstimator::Data HomographyEstimator::Prepare(const float* ref_x, const float* ref_y, const float* query_x,
                                                       const float* query_y, int count, std::vector<float>* quads) {
  quads->resize(4 * static_cast<size_t>(count));
  for (int i = 0; i < count; ++i) {
    (*quads)[4 * i] = ref_x[i];
    (*quads)[4 * i + 1] = ref_y[i];
    (*quads)[4 * i + 2] = query_x[i];
    (*quads)[4 * i + 3] = query_y[i];
  }
  return Data{ref_x, ref_y, query_x, query_y, quads->data(), count};
}

// keep[b] = 0 if sample b keeps the orientation of some of its four point triplets but flips
// others: no homography without a point at infinity between the images does that (OpenCV's
// HomographyEstimatorCallback::checkSubset applies the same test). Float is enough: a sign can
// only come out wrong for a nearly collinear triplet, rejected by Solve anyway.
__attribute__((target_clones("avx2", "default"))) void HomographyEstimator::DrawAndScreen(const RansacSampler& sampler,
                                                                                          uint32_t first_draw,
                                                                                          const Data& data,
                                                                                          SampleBatch* batch,
                                                                                          int32_t keep[kRansacLanes]) {
  sampler.DrawBatch(first_draw, batch);
  Floats8 sx[4], sy[4], dx[4], dy[4];
  GatherPoints(*batch, data.quads, sx, sy, dx, dy);
  Floats8 src_area[4], dst_area[4];
  TripletAreas(sx, sy, src_area);
  TripletAreas(dx, dy, dst_area);
  Floats8 products[4];
  for (int k = 0; k < 4; ++k) products[k] = src_area[k] * dst_area[k];
  const Ints8 result = ((products[0] < 0) & (products[1] < 0) & (products[2] < 0) & (products[3] < 0)) |
                       ((products[0] >= 0) & (products[1] >= 0) & (products[2] >= 0) & (products[3] >= 0));
  std::memcpy(keep, &result, sizeof result);
}

// Eight samples in float, one per lane. A lane is invalid if three of its points are (nearly)
// collinear in either image or if its closed-form solution is zero or not finite.
__attribute__((target_clones("avx2", "default"))) void HomographyEstimator::Solve(const SampleBatch& batch,
                                                                                  const Data& data,
                                                                                  ModelBatch<kModelSize>* out) {
  Floats8 sx[4], sy[4], dx[4], dy[4];
  GatherPoints(batch, data.quads, sx, sy, dx, dy);
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
  std::memcpy(out->model, h, sizeof h);
  const Ints8 valid = src_general & dst_general & finite;
  std::memcpy(out->valid, &valid, sizeof valid);
}

// Eight matches per step; for a count that is not a multiple of 8 the last step reloads the final
// eight and masks those already counted. Stopping once the count cannot exceed the bar leaves the
// RANSAC loop's result unchanged.
__attribute__((target_clones("avx2", "default"))) int HomographyEstimator::CountInliers(const float* model,
                                                                                        const Data& data,
                                                                                        float threshold_sq, int bar) {
  const float* h = model;
  const float *ref_x = data.ref_x, *ref_y = data.ref_y, *query_x = data.query_x, *query_y = data.query_y;
  const int count = data.count;
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
    CountEight(hv, ref_x, ref_y, query_x, query_y, count - 8, threshold, lane >= 8 - count % 8, &negative_count);
  }
  return -HorizontalSum(negative_count);
}

// The model and the arrays are copied to locals first: a store through the byte mask may alias
// anything, so reading them from memory in the loop would keep GCC from vectorising it (3.6 times
// the instructions).
void HomographyEstimator::MarkInliers(const float* model, const Data& data, float threshold_sq, uint8_t* mask) {
  float h[9];
  std::copy(model, model + 9, h);
  const float *ref_x = data.ref_x, *ref_y = data.ref_y, *query_x = data.query_x, *query_y = data.query_y;
  const int count = data.count;
  for (int i = 0; i < count; ++i) {
    const float x = ref_x[i], y = ref_y[i];
    const float w = h[6] * x + h[7] * y + h[8];
    const float du = h[0] * x + h[1] * y + h[2] - query_x[i] * w;
    const float dv = h[3] * x + h[4] * y + h[5] - query_y[i] * w;
    mask[i] = (du * du + dv * dv < threshold_sq * (w * w)) ? 1 : 0;
  }
}

bool HomographyEstimator::Refit(const Data& data, const uint8_t* mask, float* model) {
  Eigen::Matrix3d fit;
  if (!HomographyLeastSquares(data.ref_x, data.ref_y, data.query_x, data.query_y, mask, data.count, &fit)) {
    return false;
  }
  double h[9];
  for (int k = 0; k < 9; ++k) h[k] = fit(k / 3, k % 3);
  if (!NormaliseMaxAbs(h)) return false;
  for (int k = 0; k < 9; ++k) model[k] = static_cast<float>(h[k]);
  return true;
}

Eigen::Matrix3d HomographyEstimator::ToMatrix(const float* model) { return ToResultMatrix(model); }

}  // namespace hoilcd
