#include "hoilcd/bench/realism/flat_noise.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/stats.h"

namespace hoilcd {
namespace {

constexpr int kBlockPixels = kFlatBlockPx * kFlatBlockPx;
constexpr int kTerms = 6;  // 1, x, y, x², y², xy
// A residual std below this share of the block's mean magnitude is the fit's rounding: zero.
constexpr double kRoundingShare = 1e-9;

// The least-squares quadratic of a block: its design matrix (a row per pixel, row-major) and that
// matrix's pseudo-inverse, computed once. Coordinates are centred on the block for conditioning;
// the surfaces spanned, and so the residuals, are the same as with 0..15.
struct QuadraticFit {
  cv::Mat design;          // kBlockPixels x kTerms, CV_64F
  cv::Mat pseudo_inverse;  // kTerms x kBlockPixels, CV_64F
};

const QuadraticFit& BlockFit() {
  static const QuadraticFit kFit = [] {
    QuadraticFit fit;
    fit.design.create(kBlockPixels, kTerms, CV_64F);
    constexpr double kCentre = (kFlatBlockPx - 1) / 2.0;
    for (int y = 0; y < kFlatBlockPx; ++y) {
      for (int x = 0; x < kFlatBlockPx; ++x) {
        const double u = x - kCentre, v = y - kCentre;
        double* row = fit.design.ptr<double>(y * kFlatBlockPx + x);
        row[0] = 1;
        row[1] = u;
        row[2] = v;
        row[3] = u * u;
        row[4] = v * v;
        row[5] = u * v;
      }
    }
    cv::invert(fit.design, fit.pseudo_inverse, cv::DECOMP_SVD);
    return fit;
  }();
  return kFit;
}

struct Block {
  double std = 0;
  cv::Mat residual;  // kFlatBlockPx x kFlatBlockPx, CV_64F
};

// Every whole block of `frame_f64` with its quadratic removed.
std::vector<Block> QuadraticResiduals(const cv::Mat& frame_f64) {
  const QuadraticFit& fit = BlockFit();
  std::vector<Block> blocks;
  for (int y = 0; y + kFlatBlockPx <= frame_f64.rows; y += kFlatBlockPx) {
    for (int x = 0; x + kFlatBlockPx <= frame_f64.cols; x += kFlatBlockPx) {
      const cv::Mat values = frame_f64(cv::Rect(x, y, kFlatBlockPx, kFlatBlockPx)).clone().reshape(1, kBlockPixels);
      const cv::Mat fitted = fit.design * (fit.pseudo_inverse * values);
      Block b;
      const cv::Mat residual = values - fitted;
      b.residual = residual.reshape(1, kFlatBlockPx);
      cv::Scalar mean, std;
      cv::meanStdDev(b.residual, mean, std);
      b.std = std[0];
      if (b.std <= kRoundingShare * cv::norm(values, cv::NORM_L1) / kBlockPixels) {
        b.residual.setTo(0);
        b.std = 0;
      }
      blocks.push_back(std::move(b));
    }
  }
  return blocks;
}

// Σ over blocks of mean(r(p) r(p + (dx, dy))) / Σ over blocks of mean(r²).
double PooledCorrelation(const std::vector<const Block*>& blocks, int dx, int dy) {
  double shared = 0, power = 0;
  for (const Block* b : blocks) {
    const cv::Mat& r = b->residual;
    const cv::Mat a = r(cv::Rect(0, 0, r.cols - dx, r.rows - dy));
    const cv::Mat shifted = r(cv::Rect(dx, dy, r.cols - dx, r.rows - dy));
    shared += a.dot(shifted) / static_cast<double>(a.total());
    power += r.dot(r) / static_cast<double>(r.total());
  }
  return power > 0 ? shared / power : NAN;
}

}  // namespace

FlatNoise MeasureFlatNoise(const cv::Mat& frame) {
  HOILCD_CHECK(frame.channels() == 1 && !frame.empty());
  cv::Mat f;
  frame.convertTo(f, CV_64F);
  const std::vector<Block> blocks = QuadraticResiduals(f);
  FlatNoise out;
  if (blocks.empty()) return out;
  std::vector<size_t> order(blocks.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return blocks[a].std < blocks[b].std; });
  const size_t keep =
      std::max<size_t>(1, static_cast<size_t>(std::floor(static_cast<double>(blocks.size()) * kFlatBlockShare + 1e-9)));
  std::vector<const Block*> kept;
  std::vector<double> stds;
  for (size_t i = 0; i < keep; ++i) {
    kept.push_back(&blocks[order[i]]);
    stds.push_back(blocks[order[i]].std);
  }
  out.blocks = static_cast<int>(keep);
  out.std = Median(stds);
  out.lag1_x = PooledCorrelation(kept, 1, 0);
  out.lag1_y = PooledCorrelation(kept, 0, 1);
  out.lag1 = (out.lag1_x + out.lag1_y) / 2;
  return out;
}

}  // namespace hoilcd
