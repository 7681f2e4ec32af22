#include "hoilcd/sim/sensor/optics.h"

#include <cmath>
#include <cstdint>
#include <vector>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/sim/sensor/radiometry.h"

namespace hoilcd {
namespace {

// Wavelengths sampled across the band for the polychromatic MTF; the MTF changes smoothly with λ,
// so 49 Simpson nodes leave it exact to about 1e-7.
constexpr int kBandIntervals = 48;
// Rows per parallel chunk of the DCT.
constexpr int64_t kRowsPerChunk = 32;

double Sinc(double x) {
  if (x == 0.0) return 1.0;
  const double a = M_PI * x;
  return std::sin(a) / a;
}

// Simpson weights of the band's wavelengths, each by its Planck spectral radiance, summing to 1.
struct BandSamples {
  std::vector<double> lambda_um, weight;
};

BandSamples SampleBand(const PixelResponse& r) {
  BandSamples band;
  double total = 0.0;
  for (int i = 0; i <= kBandIntervals; ++i) {
    const double lambda_um = r.lambda_min_um + (r.lambda_max_um - r.lambda_min_um) * i / kBandIntervals;
    const double simpson = (i == 0 || i == kBandIntervals) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
    const double w = simpson * PlanckSpectral(lambda_um * 1e-6, r.band_temperature_k);
    band.lambda_um.push_back(lambda_um);
    band.weight.push_back(w);
    total += w;
  }
  for (double& w : band.weight) w /= total;
  return band;
}

double DiffractionMtf(const BandSamples& band, const PixelResponse& r, double f_cycles_per_px) {
  double mtf = 0.0;
  for (size_t i = 0; i < band.lambda_um.size(); ++i) {
    mtf += band.weight[i] * CircularApertureMtf(f_cycles_per_px * band.lambda_um[i] * r.f_number / r.pixel_pitch_um);
  }
  return mtf;
}

double MtfAt(const BandSamples& band, const PixelResponse& r, double fx, double fy) {
  const double absorber = std::sqrt(r.fill_factor);  // its side, in pixels
  const double sigma = r.aberration_sigma_px;
  return DiffractionMtf(band, r, std::hypot(fx, fy)) * Sinc(absorber * fx) * Sinc(absorber * fy) *
         std::exp(-2.0 * M_PI * M_PI * sigma * sigma * (fx * fx + fy * fy));
}

void CheckResponse(const PixelResponse& r) {
  HOILCD_CHECK_MSG(r.f_number > 0 && r.pixel_pitch_um > 0 && r.fill_factor > 0 && r.fill_factor <= 1 &&
                       r.aberration_sigma_px >= 0 && r.lambda_min_um > 0 && r.lambda_max_um > r.lambda_min_um &&
                       r.band_temperature_k > 0,
                   "pixel response: f/" << r.f_number << ", pitch " << r.pixel_pitch_um << " µm, fill " << r.fill_factor
                                        << ", aberration " << r.aberration_sigma_px << " px");
}

// The 1-D DCT (or its inverse) of each row of `in` into `out`, chunks of rows in parallel
// (cv::DCT_ROWS transforms each row on its own, so the result does not depend on the chunks).
void DctRows(const cv::Mat& in, cv::Mat* out, int flags, int num_threads) {
  out->create(in.size(), CV_32F);
  ParallelForChunks(in.rows, kRowsPerChunk, num_threads, [&](int64_t begin, int64_t end, int) {
    cv::Mat rows = out->rowRange(static_cast<int>(begin), static_cast<int>(end));
    cv::dct(in.rowRange(static_cast<int>(begin), static_cast<int>(end)), rows, flags | cv::DCT_ROWS);
  });
}

}  // namespace

double CircularApertureMtf(double nu) {
  nu = std::abs(nu);
  if (nu >= 1.0) return 0.0;
  return (2.0 / M_PI) * (std::acos(nu) - nu * std::sqrt(1.0 - nu * nu));
}

double PixelResponseMtf(const PixelResponse& response, double fx, double fy) {
  CheckResponse(response);
  return MtfAt(SampleBand(response), response, fx, fy);
}

PixelResponseFilter::PixelResponseFilter(const PixelResponse& response, int width, int height)
    : width_(width), height_(height) {
  CheckResponse(response);
  HOILCD_CHECK_MSG(width > 0 && height > 0, width << "x" << height);
  const BandSamples band = SampleBand(response);
  const int even_w = width + width % 2, even_h = height + height % 2;
  // Stored transposed (row u, column v): the gain applies between the columns' two passes.
  gain_t_.create(even_w, even_h, CV_32F);
  for (int u = 0; u < even_w; ++u) {
    for (int v = 0; v < even_h; ++v) {
      gain_t_.at<float>(u, v) = static_cast<float>(MtfAt(band, response, u / (2.0 * even_w), v / (2.0 * even_h)));
    }
  }
}

void PixelResponseFilter::Apply(const cv::Mat& radiance, cv::Mat* out, int num_threads) const {
  HOILCD_CHECK_MSG(radiance.type() == CV_32FC1 && radiance.cols == width_ && radiance.rows == height_,
                   "radiance must be CV_32F " << width_ << "x" << height_);
  HOILCD_CHECK(out != nullptr && out->data != radiance.data);
  const bool evened = gain_t_.cols != height_ || gain_t_.rows != width_;
  cv::Mat even = radiance;
  if (evened)
    cv::copyMakeBorder(radiance, even, 0, gain_t_.cols - height_, 0, gain_t_.rows - width_, cv::BORDER_REFLECT);
  // The 2-D DCT separates: the rows, then the columns as the rows of the transpose.
  cv::Mat rows, columns, filtered_columns, filtered;
  DctRows(even, &rows, 0, num_threads);
  DctRows(rows.t(), &columns, 0, num_threads);
  DctRows(columns.mul(gain_t_), &filtered_columns, cv::DCT_INVERSE, num_threads);
  DctRows(filtered_columns.t(), evened ? &filtered : out, cv::DCT_INVERSE, num_threads);
  if (evened) filtered(cv::Rect(0, 0, width_, height_)).copyTo(*out);
}

}  // namespace hoilcd
