#include "hoilcd/core/homography_ransac.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "hoilcd/core/error.h"
#include "hoilcd/core/random.h"

namespace hoilcd {
namespace {

// A sample triplet whose angle sine at any vertex is below this is treated as collinear.
constexpr double kMinSampleSine = 1e-3;
// With redraw_degenerate_samples, at most trials * this many samples are drawn in all.
constexpr int64_t kMaxDrawsPerTrial = 10;

// Signed doubled areas of the point triplets (0,1,2), (0,1,3), (0,2,3), (1,2,3) of a sample.
// With a, b, c = p1, p2, p3 minus p0, the area of (1,2,3) is b×c + a×b - a×c.
template <typename Real>
inline void TripletAreas(const Real x[4], const Real y[4], Real area[4]) {
  const Real ax = x[1] - x[0], ay = y[1] - y[0];
  const Real bx = x[2] - x[0], by = y[2] - y[0];
  const Real cx = x[3] - x[0], cy = y[3] - y[0];
  area[0] = ax * by - ay * bx;
  area[1] = ax * cy - ay * cx;
  area[2] = bx * cy - by * cx;
  area[3] = area[2] + area[0] - area[1];
}

// Samples drawn and pre-checked together, lane b holding sample b (structure of arrays).
constexpr int kBatch = 8;
struct SampleBatch {
  uint32_t idx[kBatch][4] = {};
  float sx[4][kBatch] = {}, sy[4][kBatch] = {}, dx[4][kBatch] = {}, dy[4][kBatch] = {};
  int32_t consistent[kBatch] = {};
};

// consistent[b] = 0 if sample b keeps the orientation of some of its four point triplets but
// flips others: no homography without a point at infinity between the images does that
// (OpenCV's HomographyEstimatorCallback::checkSubset applies the same test). Lane-parallel, as
// most random samples fail it. Float is enough: a sign can only come out wrong for a nearly
// collinear triplet, which GeneralPosition rejects anyway.
__attribute__((target_clones("avx2", "default"))) void CheckOrientations(SampleBatch* batch) {
  for (int b = 0; b < kBatch; ++b) {
    float src[4], dst[4];
    const float qx[4] = {batch->sx[0][b], batch->sx[1][b], batch->sx[2][b], batch->sx[3][b]};
    const float qy[4] = {batch->sy[0][b], batch->sy[1][b], batch->sy[2][b], batch->sy[3][b]};
    const float px[4] = {batch->dx[0][b], batch->dx[1][b], batch->dx[2][b], batch->dx[3][b]};
    const float py[4] = {batch->dy[0][b], batch->dy[1][b], batch->dy[2][b], batch->dy[3][b]};
    TripletAreas(qx, qy, src);
    TripletAreas(px, py, dst);
    const float p0 = src[0] * dst[0], p1 = src[1] * dst[1], p2 = src[2] * dst[2],
                p3 = src[3] * dst[3];
    const float lowest = std::min(std::min(p0, p1), std::min(p2, p3));
    const float highest = std::max(std::max(p0, p1), std::max(p2, p3));
    batch->consistent[b] = (highest < 0) | (lowest >= 0);
  }
}

// Draws `size` samples of 4 distinct indices in [0, n) from rng, in lane order, and checks them.
void DrawBatch(Rng& rng, uint32_t n, int size, const float* ref_x, const float* ref_y,
               const float* query_x, const float* query_y, SampleBatch* batch) {
  for (int b = 0; b < size; ++b) {
    uint32_t* idx = batch->idx[b];
    idx[0] = rng.UniformInt(n);
    do idx[1] = rng.UniformInt(n); while (idx[1] == idx[0]);
    do idx[2] = rng.UniformInt(n); while (idx[2] == idx[0] || idx[2] == idx[1]);
    do idx[3] = rng.UniformInt(n); while (idx[3] == idx[0] || idx[3] == idx[1] || idx[3] == idx[2]);
    for (int k = 0; k < 4; ++k) {
      batch->sx[k][b] = ref_x[idx[k]];
      batch->sy[k][b] = ref_y[idx[k]];
      batch->dx[k][b] = query_x[idx[k]];
      batch->dy[k][b] = query_y[idx[k]];
    }
  }
  CheckOrientations(batch);
}

// True if no triplet is (nearly) collinear: area² > sine² · |edge1|² · |edge2|² for the two
// edges at the triplet's first vertex.
inline bool GeneralPosition(const double x[4], const double y[4], const double area[4]) {
  const double ax = x[1] - x[0], ay = y[1] - y[0];
  const double bx = x[2] - x[0], by = y[2] - y[0];
  const double cx = x[3] - x[0], cy = y[3] - y[0];
  const double ex = bx - ax, ey = by - ay, fx = cx - ax, fy = cy - ay;  // p2 - p1, p3 - p1
  const double a2 = ax * ax + ay * ay, b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
  const double e2 = ex * ex + ey * ey, f2 = fx * fx + fy * fy;
  const double edges[4] = {a2 * b2, a2 * c2, b2 * c2, e2 * f2};
  constexpr double kSineSq = kMinSampleSine * kMinSampleSine;
  int collinear = 0;
  for (int k = 0; k < 4; ++k) collinear |= area[k] * area[k] <= kSineSq * edges[k] ? 1 : 0;
  return collinear == 0;
}

// Unit square (0,0),(1,0),(1,1),(0,1) -> quad (x[i], y[i]) (Heckbert 1989), up to scale,
// row-major; division-free so a general-position quad gives a finite, non-singular matrix.
inline void SquareToQuad(const double x[4], const double y[4], double m[9]) {
  const double sx = x[0] - x[1] + x[2] - x[3];
  const double sy = y[0] - y[1] + y[2] - y[3];
  const double dx1 = x[1] - x[2], dx2 = x[3] - x[2];
  const double dy1 = y[1] - y[2], dy2 = y[3] - y[2];
  const double den = dx1 * dy2 - dx2 * dy1;
  const double g = sx * dy2 - dx2 * sy;
  const double h = dx1 * sy - sx * dy1;
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
inline void Adjugate(const double m[9], double a[9]) {
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

inline void Multiply3(const double a[9], const double b[9], double c[9]) {
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) {
      c[3 * r + k] = a[3 * r] * b[k] + a[3 * r + 1] * b[3 + k] + a[3 * r + 2] * b[6 + k];
    }
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

// Scales h so its largest entry has magnitude 1; false if h is zero or not finite.
inline bool NormaliseMaxAbs(double h[9]) {
  double largest = 0;
  for (int i = 0; i < 9; ++i) largest = std::max(largest, std::abs(h[i]));
  if (!(largest > 0) || !std::isfinite(largest)) return false;
  const double inv = 1.0 / largest;
  for (int i = 0; i < 9; ++i) h[i] *= inv;
  return true;
}

// Closed-form 4-point homography src -> dst on coordinates centred on each set's centroid,
// scaled to max |h| = 1; the caller has checked that both quads are in general position.
// Scaling as well would not help: the closed form is a polynomial in the coordinates, and
// floating-point relative error is scale-invariant.
inline bool ClosedFormHomography(const double sx[4], const double sy[4], const double dx[4],
                                 const double dy[4], double h[9]) {
  const double scx = 0.25 * (sx[0] + sx[1] + sx[2] + sx[3]);
  const double scy = 0.25 * (sy[0] + sy[1] + sy[2] + sy[3]);
  const double dcx = 0.25 * (dx[0] + dx[1] + dx[2] + dx[3]);
  const double dcy = 0.25 * (dy[0] + dy[1] + dy[2] + dy[3]);
  double nsx[4], nsy[4], ndx[4], ndy[4];
  for (int i = 0; i < 4; ++i) {
    nsx[i] = sx[i] - scx;
    nsy[i] = sy[i] - scy;
    ndx[i] = dx[i] - dcx;
    ndy[i] = dy[i] - dcy;
  }
  double square_to_src[9], square_to_dst[9], src_to_square[9], hn[9];
  SquareToQuad(nsx, nsy, square_to_src);
  SquareToQuad(ndx, ndy, square_to_dst);
  Adjugate(square_to_src, src_to_square);
  Multiply3(square_to_dst, src_to_square, hn);
  // H = T(dst centroid) · Hn · T(-src centroid).
  for (int r = 0; r < 3; ++r) hn[3 * r + 2] -= scx * hn[3 * r] + scy * hn[3 * r + 1];
  for (int k = 0; k < 3; ++k) {
    h[k] = hn[k] + dcx * hn[6 + k];
    h[3 + k] = hn[3 + k] + dcy * hn[6 + k];
    h[6 + k] = hn[6 + k];
  }
  return NormaliseMaxAbs(h);
}

// Matches per block of the inlier count; after each block the count gives up if it can no
// longer beat the bar, which leaves the result of the RANSAC loop unchanged.
constexpr int kInlierBlock = 64;

// Inlier count of h over all matches, or some count <= bar once it cannot exceed bar. The block
// loop is division-free so GCC vectorises it at -O3:
// |(u, v) / w - q| < t  <=>  |(u, v) - q w|² < t² w²  (false when w = 0). Cloned for AVX2 with a
// run-time dispatch (the build has no -march); lane width does not change the float results.
__attribute__((target_clones("avx2", "default"))) int CountInliers(
    const float h[9], const float* ref_x, const float* ref_y, const float* query_x,
    const float* query_y, int count, float threshold_sq, int bar) {
  const float h0 = h[0], h1 = h[1], h2 = h[2], h3 = h[3], h4 = h[4], h5 = h[5], h6 = h[6],
              h7 = h[7], h8 = h[8];
  int inliers = 0;
  for (int begin = 0; begin < count; begin += kInlierBlock) {
    const int end = std::min(count, begin + kInlierBlock);
    int block_inliers = 0;
    for (int i = begin; i < end; ++i) {
      const float x = ref_x[i], y = ref_y[i];
      const float w = h6 * x + h7 * y + h8;
      const float du = h0 * x + h1 * y + h2 - query_x[i] * w;
      const float dv = h3 * x + h4 * y + h5 - query_y[i] * w;
      block_inliers += (du * du + dv * dv < threshold_sq * (w * w)) ? 1 : 0;
    }
    inliers += block_inliers;
    if (inliers + (count - end) <= bar) return inliers;
  }
  return inliers;
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

void ToFloat(const double h[9], float f[9]) {
  for (int i = 0; i < 9; ++i) f[i] = static_cast<float>(h[i]);
}

Eigen::Matrix3d ToResultMatrix(const double h[9]) {
  Eigen::Matrix3d m;
  m << h[0], h[1], h[2], h[3], h[4], h[5], h[6], h[7], h[8];
  if (std::abs(m(2, 2)) > 1e-12 * m.cwiseAbs().maxCoeff()) m /= m(2, 2);
  return m;
}

}  // namespace

std::string RansacOptions::Check() const {
  std::ostringstream out;
  if (trials < 1) out << "trials must be >= 1 (got " << trials << "); ";
  if (!(inlier_threshold_px > 0) || !std::isfinite(inlier_threshold_px)) {
    out << "inlier_threshold_px must be a positive number of pixels (got " << inlier_threshold_px
        << "); ";
  }
  if (local_optimisation_refits < 0) {
    out << "local_optimisation_refits must be >= 0 (got " << local_optimisation_refits << "); ";
  }
  std::string text = out.str();
  if (!text.empty()) text.resize(text.size() - 2);
  return text;
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
  if (!GeneralPosition(sx, sy, src_area) || !GeneralPosition(dx, dy, dst_area)) return false;
  if (!ClosedFormHomography(sx, sy, dx, dy, m)) return false;
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
    rd += std::hypot(ref_x[i] - rcx, ref_y[i] - rcy);
    qd += std::hypot(query_x[i] - qcx, query_y[i] - qcy);
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
  const float threshold_sq =
      static_cast<float>(options.inlier_threshold_px * options.inlier_threshold_px);
  Rng rng(seed);
  const uint32_t n = static_cast<uint32_t>(count);
  // With exactly 4 matches every sample is the same set: one draw decides.
  const int64_t draw_budget =
      count == 4 ? 1
                 : static_cast<int64_t>(options.trials) *
                       (options.redraw_degenerate_samples ? kMaxDrawsPerTrial : 1);
  double best[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  int best_inliers = 0;
  std::vector<uint8_t> lo_mask;
  int hypotheses = 0;
  SampleBatch batch;
  int lane = 0, batch_size = 0;  // next lane to use, lanes drawn
  for (int64_t draws = 0; hypotheses < options.trials && draws < draw_budget; ++draws) {
    if (lane == batch_size) {
      batch_size = static_cast<int>(std::min<int64_t>(kBatch, draw_budget - draws));
      DrawBatch(rng, n, batch_size, ref_x, ref_y, query_x, query_y, &batch);
      lane = 0;
    }
    const int b = lane++;
    if (!batch.consistent[b]) continue;
    double sx[4], sy[4], dx[4], dy[4], src_area[4], dst_area[4], h[9];
    for (int k = 0; k < 4; ++k) {
      sx[k] = batch.sx[k][b];
      sy[k] = batch.sy[k][b];
      dx[k] = batch.dx[k][b];
      dy[k] = batch.dy[k][b];
    }
    TripletAreas(sx, sy, src_area);
    TripletAreas(dx, dy, dst_area);
    if (!GeneralPosition(sx, sy, src_area) || !GeneralPosition(dx, dy, dst_area) ||
        !ClosedFormHomography(sx, sy, dx, dy, h)) {
      continue;
    }
    ++hypotheses;
    float hf[9];
    ToFloat(h, hf);
    const int inliers =
        CountInliers(hf, ref_x, ref_y, query_x, query_y, count, threshold_sq, best_inliers);
    if (inliers <= best_inliers) continue;
    best_inliers = inliers;
    std::copy(h, h + 9, best);
    if (options.local_optimisation_refits <= 0 || inliers <= 4) continue;
    lo_mask.resize(count);
    MarkInliers(hf, ref_x, ref_y, query_x, query_y, count, threshold_sq, lo_mask.data());
    for (int refit = 0; refit < options.local_optimisation_refits; ++refit) {
      Eigen::Matrix3d fit;
      if (!HomographyLeastSquares(ref_x, ref_y, query_x, query_y, lo_mask.data(), count, &fit)) {
        break;
      }
      double hr[9];
      for (int k = 0; k < 9; ++k) hr[k] = fit(k / 3, k % 3);
      if (!NormaliseMaxAbs(hr)) break;
      ToFloat(hr, hf);
      const int refit_inliers =
          CountInliers(hf, ref_x, ref_y, query_x, query_y, count, threshold_sq, best_inliers);
      if (refit_inliers <= best_inliers) break;
      best_inliers = refit_inliers;
      std::copy(hr, hr + 9, best);
      MarkInliers(hf, ref_x, ref_y, query_x, query_y, count, threshold_sq, lo_mask.data());
    }
  }
  if (best_h != nullptr) *best_h = ToResultMatrix(best);
  if (inlier_mask != nullptr) {
    if (best_inliers == 0) {
      std::fill(inlier_mask, inlier_mask + count, uint8_t{0});
    } else {
      float hf[9];
      ToFloat(best, hf);
      MarkInliers(hf, ref_x, ref_y, query_x, query_y, count, threshold_sq, inlier_mask);
    }
  }
  return best_inliers;
}

HomographyResult EstimateHomographyRansac(const std::vector<Point2>& query,
                                          const std::vector<Point2>& reference,
                                          const std::vector<Correspondence>& matches,
                                          const RansacOptions& options, uint64_t seed) {
  const std::string problem = options.Check();
  HOILCD_CHECK_MSG(problem.empty(), problem);
  const int count = static_cast<int>(matches.size());
  std::vector<float> ref_x(count), ref_y(count), query_x(count), query_y(count);
  for (int i = 0; i < count; ++i) {
    const Correspondence& m = matches[i];
    HOILCD_CHECK_MSG(m.query >= 0 && m.query < static_cast<int>(query.size()) &&
                         m.reference >= 0 && m.reference < static_cast<int>(reference.size()),
                     "match " << i << " (" << m.query << ", " << m.reference
                              << ") is out of range");
    ref_x[i] = reference[m.reference].x;
    ref_y[i] = reference[m.reference].y;
    query_x[i] = query[m.query].x;
    query_y[i] = query[m.query].y;
  }
  HomographyResult result;
  result.inlier_mask.resize(count);
  result.inliers = RansacHomographySoa(ref_x.data(), ref_y.data(), query_x.data(), query_y.data(),
                                       count, options, seed, &result.reference_to_query,
                                       result.inlier_mask.data());
  return result;
}

}  // namespace hoilcd
