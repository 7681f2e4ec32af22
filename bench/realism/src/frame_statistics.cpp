#include "hoilcd/bench/realism/frame_statistics.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "hoilcd/bench/realism/flat_noise.h"
#include "hoilcd/core/features/keypoints.h"
#include "hoilcd/core/util/error.h"

namespace hoilcd {
namespace {

constexpr double kQuantumK = 0.01;  // of the median filter's histogram
constexpr int kMinWallPixels = 100;

// The q-quantile (0..1) of a CV_32F image's values, linear between order statistics.
double ImageQuantile(const cv::Mat& values_f32, double q) {
  std::vector<float> v;
  v.reserve(values_f32.total());
  for (int y = 0; y < values_f32.rows; ++y) {
    const float* row = values_f32.ptr<float>(y);
    v.insert(v.end(), row, row + values_f32.cols);
  }
  if (v.empty()) return NAN;
  const double pos = q * static_cast<double>(v.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(pos));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(lo), v.end());
  const double a = v[lo];
  if (lo + 1 >= v.size()) return a;
  const double b = *std::min_element(v.begin() + static_cast<std::ptrdiff_t>(lo) + 1, v.end());
  return a + (pos - static_cast<double>(lo)) * (b - a);
}

cv::Mat AsFloat(const cv::Mat& frame) {
  HOILCD_CHECK(frame.channels() == 1 && !frame.empty());
  cv::Mat f;
  frame.convertTo(f, CV_32F);
  return f;
}

cv::Mat ResizedToStatisticsSize(const cv::Mat& f32) {
  if (f32.cols == kStatisticsWidthPx && f32.rows == kStatisticsHeightPx) return f32;
  cv::Mat out;
  cv::resize(f32, out, cv::Size(kStatisticsWidthPx, kStatisticsHeightPx), 0, 0, cv::INTER_AREA);
  return out;
}

// The 1st..99th percentile of `frame` onto 0..255 (clamped), CV_32F at its native size.
cv::Mat StretchedFloat(const cv::Mat& frame) {
  const cv::Mat f = AsFloat(frame);
  const double p1 = ImageQuantile(f, 0.01);
  const double p99 = ImageQuantile(f, 0.99);
  cv::Mat stretched(f.size(), CV_32F, cv::Scalar(0));
  if (p99 > p1) {
    f.convertTo(stretched, CV_32F, 255.0 / (p99 - p1), -p1 * 255.0 / (p99 - p1));
    cv::min(cv::max(stretched, 0.0), 255.0, stretched);
  }
  return stretched;
}

cv::Mat RoundedToU8(const cv::Mat& f32) {
  cv::Mat u8;
  f32.convertTo(u8, CV_8U);  // rounds
  return u8;
}

// The statistics of the stretched frame: resized (`stretched`) and the one for the slope (`spectrum`).
FrameStatistics ImageStatistics(const cv::Mat& stretched, const cv::Mat& spectrum) {
  FrameStatistics s;
  s.shi_tomasi_corners = ShiTomasiCorners(stretched);
  s.slcd_corners = SlcdCorners(stretched);
  s.fast_corners = FastCorners(stretched);
  s.strong_edge_fraction = StrongEdgeFraction(stretched);
  s.entropy_bits = EntropyBits(stretched);
  s.spectrum_slope = SpectrumSlope(spectrum);
  return s;
}

// The image statistics of `frame` (native size, stretched once), its size and its flat-region
// noise's correlation (the noise's level only where `frame` holds temperatures).
FrameStatistics NativeFrameStatistics(const cv::Mat& frame, bool temperatures) {
  const cv::Mat stretched = StretchedFloat(frame);
  const cv::Mat resized = RoundedToU8(ResizedToStatisticsSize(stretched));
  FrameStatistics s =
      ImageStatistics(resized, SmallerThanStatisticsSize(frame.size()) ? RoundedToU8(stretched) : resized);
  s.width_px = frame.cols;
  s.height_px = frame.rows;
  const FlatNoise noise = MeasureFlatNoise(frame);
  s.flat_noise_lag1 = noise.lag1;
  if (temperatures) s.flat_noise_k = noise.std;
  return s;
}

}  // namespace

cv::Mat StretchedFrame(const cv::Mat& frame) { return RoundedToU8(ResizedToStatisticsSize(StretchedFloat(frame))); }

cv::Mat NativeStretchedFrame(const cv::Mat& frame) { return RoundedToU8(StretchedFloat(frame)); }

bool SmallerThanStatisticsSize(cv::Size size) {
  return size.width < kStatisticsWidthPx || size.height < kStatisticsHeightPx;
}

cv::Mat SpectrumFrame(const cv::Mat& frame) {
  return SmallerThanStatisticsSize(frame.size()) ? NativeStretchedFrame(frame) : StretchedFrame(frame);
}

cv::Mat ResizedTemperatures(const cv::Mat& temperature_c) { return ResizedToStatisticsSize(AsFloat(temperature_c)); }

int ShiTomasiCorners(const cv::Mat& stretched_u8) {
  constexpr int kBorderPx = 4;
  cv::Mat mask(stretched_u8.size(), CV_8U, cv::Scalar(0));
  if (stretched_u8.cols > 2 * kBorderPx && stretched_u8.rows > 2 * kBorderPx) {
    mask(cv::Rect(kBorderPx, kBorderPx, stretched_u8.cols - 2 * kBorderPx, stretched_u8.rows - 2 * kBorderPx)) = 255;
  }
  std::vector<cv::Point2f> corners;
  cv::goodFeaturesToTrack(stretched_u8, corners, 1000, 0.01, 4, mask, 3, false, 0.04);
  return static_cast<int>(corners.size());
}

int SlcdCorners(const cv::Mat& stretched_u8) {
  static const KeypointOptions kSlcd;  // the SLCD detector's defaults (keypoints.cpp's table)
  return static_cast<int>(DetectKeypoints(stretched_u8, kSlcd).size());
}

int FastCorners(const cv::Mat& stretched_u8) {
  std::vector<cv::KeyPoint> keypoints;
  cv::FAST(stretched_u8, keypoints, 10, true);
  return static_cast<int>(keypoints.size());
}

double StrongEdgeFraction(const cv::Mat& stretched_u8) {
  cv::Mat dx, dy, magnitude;
  cv::Sobel(stretched_u8, dx, CV_32F, 1, 0, 3);
  cv::Sobel(stretched_u8, dy, CV_32F, 0, 1, 3);
  cv::magnitude(dx, dy, magnitude);
  // The 3x3 Sobel kernel's weights sum to 8 on each side: magnitude / 8 is in grey levels per pixel.
  const int strong = cv::countNonZero(magnitude > 8.0 * 8.0);
  return static_cast<double>(strong) / static_cast<double>(stretched_u8.total());
}

double EntropyBits(const cv::Mat& stretched_u8) {
  std::vector<double> counts(256, 0.0);
  for (int y = 0; y < stretched_u8.rows; ++y) {
    const uint8_t* row = stretched_u8.ptr<uint8_t>(y);
    for (int x = 0; x < stretched_u8.cols; ++x) counts[row[x]] += 1;
  }
  const double n = static_cast<double>(stretched_u8.total());
  double bits = 0;
  for (double c : counts) {
    if (c > 0) bits -= c / n * std::log2(c / n);
  }
  return bits;
}

double SpectrumSlope(const cv::Mat& stretched_u8) {
  cv::Mat f;
  stretched_u8.convertTo(f, CV_64F);
  f -= cv::mean(f)[0];
  cv::Mat spectrum;
  cv::dft(f, spectrum, cv::DFT_COMPLEX_OUTPUT);
  const int w = f.cols, h = f.rows;
  constexpr double kRingWidth = 1.0 / 256.0;  // cycles/px
  constexpr double kLow = 1.0 / 64.0, kHigh = 1.0 / 4.0;
  const int rings = static_cast<int>(std::lround(kHigh / kRingWidth)) + 1;
  std::vector<double> power(static_cast<size_t>(rings), 0.0), count(static_cast<size_t>(rings), 0.0);
  for (int y = 0; y < h; ++y) {
    const double fy = static_cast<double>(y <= h / 2 ? y : y - h) / h;
    const cv::Vec2d* row = spectrum.ptr<cv::Vec2d>(y);
    for (int x = 0; x < w; ++x) {
      const double fx = static_cast<double>(x <= w / 2 ? x : x - w) / w;
      const long ring = std::lround(std::hypot(fx, fy) / kRingWidth);
      if (ring >= rings) continue;
      power[static_cast<size_t>(ring)] += row[x][0] * row[x][0] + row[x][1] * row[x][1];
      count[static_cast<size_t>(ring)] += 1;
    }
  }
  double sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
  for (int r = 0; r < rings; ++r) {
    const double freq = r * kRingWidth;
    if (freq < kLow - 1e-12 || freq > kHigh + 1e-12 || count[static_cast<size_t>(r)] == 0) continue;
    const double mean_power = power[static_cast<size_t>(r)] / count[static_cast<size_t>(r)];
    if (!(mean_power > 0)) return NAN;
    const double lx = std::log(freq), ly = std::log(mean_power);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
    n += 1;
  }
  const double denominator = n * sxx - sx * sx;
  return n >= 2 && denominator > 0 ? (n * sxy - sx * sy) / denominator : NAN;
}

cv::Mat MedianFilter15(const cv::Mat& temperature_c) {
  const cv::Mat t = AsFloat(temperature_c);
  constexpr int kRadius = kWallMedianWindowPx / 2;
  constexpr int kHalf = kWallMedianWindowPx * kWallMedianWindowPx / 2;  // index of the median, 112
  double lo = 0, hi = 0;
  cv::minMaxLoc(t, &lo, &hi);
  const int bins = static_cast<int>(std::lround((hi - lo) / kQuantumK)) + 1;
  cv::Mat q(t.size(), CV_32S);
  for (int y = 0; y < t.rows; ++y) {
    for (int x = 0; x < t.cols; ++x)
      q.at<int>(y, x) = static_cast<int>(std::lround((t.at<float>(y, x) - lo) / kQuantumK));
  }
  const auto at = [&](int y, int x) { return q.at<int>(std::clamp(y, 0, t.rows - 1), std::clamp(x, 0, t.cols - 1)); };
  cv::Mat out(t.size(), CV_32F);
  std::vector<int> hist(static_cast<size_t>(bins));
  for (int y = 0; y < t.rows; ++y) {
    std::fill(hist.begin(), hist.end(), 0);
    for (int dy = -kRadius; dy <= kRadius; ++dy) {
      for (int dx = -kRadius; dx <= kRadius; ++dx) ++hist[static_cast<size_t>(at(y + dy, dx))];
    }
    int m = 0, below = 0;  // the median bin and how many values lie below it
    while (below + hist[static_cast<size_t>(m)] <= kHalf) below += hist[static_cast<size_t>(m++)];
    for (int x = 0;; ++x) {
      out.at<float>(y, x) = static_cast<float>(lo + m * kQuantumK);
      if (x + 1 == t.cols) break;
      for (int dy = -kRadius; dy <= kRadius; ++dy) {
        const int gone = at(y + dy, x - kRadius), come = at(y + dy, x + kRadius + 1);
        --hist[static_cast<size_t>(gone)];
        below -= gone < m;
        ++hist[static_cast<size_t>(come)];
        below += come < m;
      }
      while (below > kHalf) below -= hist[static_cast<size_t>(--m)];
      while (below + hist[static_cast<size_t>(m)] <= kHalf) below += hist[static_cast<size_t>(m++)];
    }
  }
  return out;
}

double WallResidualK(const cv::Mat& temperature_c, double* share) {
  const cv::Mat t = AsFloat(temperature_c);
  const double median = ImageQuantile(t, 0.5);
  const cv::Mat filtered = MedianFilter15(t);
  double sum = 0, sum_sq = 0;
  int n = 0;
  for (int y = 0; y < t.rows; ++y) {
    for (int x = 0; x < t.cols; ++x) {
      const double v = t.at<float>(y, x);
      if (std::fabs(v - median) > kWallBandK) continue;
      const double r = v - filtered.at<float>(y, x);
      sum += r;
      sum_sq += r * r;
      ++n;
    }
  }
  if (share != nullptr) *share = static_cast<double>(n) / static_cast<double>(t.total());
  if (n < kMinWallPixels) return NAN;
  const double mean = sum / n;
  return std::sqrt(std::max(0.0, sum_sq / n - mean * mean));
}

FrameStatistics MeasureTemperatureFrame(const cv::Mat& temperature_c) {
  const cv::Mat t = ResizedTemperatures(temperature_c);
  FrameStatistics s = NativeFrameStatistics(temperature_c, true);
  s.radiometric = true;
  s.p1_c = ImageQuantile(t, 0.01);
  s.p5_c = ImageQuantile(t, 0.05);
  s.p50_c = ImageQuantile(t, 0.50);
  s.p95_c = ImageQuantile(t, 0.95);
  s.p99_c = ImageQuantile(t, 0.99);
  s.spread_k = s.p95_c - s.p5_c;
  s.wall_residual_k = WallResidualK(t, &s.wall_share);
  s.wall_dominated = s.wall_share >= kWallDominatedShare;
  s.blank = s.spread_k < kBlankViewSpreadK;
  return s;
}

FrameStatistics MeasureGreyFrame(const cv::Mat& grey) { return NativeFrameStatistics(grey, false); }

double TemporalNoiseK(const cv::Mat& first_c, const cv::Mat& second_c) {
  HOILCD_CHECK(first_c.size() == second_c.size());
  const cv::Mat diff = ResizedTemperatures(second_c) - ResizedTemperatures(first_c);
  const double median = ImageQuantile(diff, 0.5);
  const cv::Mat deviation = cv::abs(diff - median);
  return 1.4826 * ImageQuantile(deviation, 0.5) / std::sqrt(2.0);
}

const std::vector<StatisticInfo>& FrameStatisticList() {
  static const std::vector<StatisticInfo> kList = {
      {"shi_tomasi_corners", "Shi-Tomasi corners", "", false,
       [](const FrameStatistics& s) { return s.shi_tomasi_corners; }},
      {"slcd_corners", "corners of the SLCD detector (its defaults)", "", false,
       [](const FrameStatistics& s) { return s.slcd_corners; }},
      {"fast_corners", "FAST corners (threshold 10)", "", false,
       [](const FrameStatistics& s) { return s.fast_corners; }},
      {"strong_edge_fraction", "strong-edge fraction", "", false,
       [](const FrameStatistics& s) { return s.strong_edge_fraction; }},
      {"entropy_bits", "entropy", "bits", false, [](const FrameStatistics& s) { return s.entropy_bits; }},
      {"spectrum_slope", "spectrum slope (log power vs log frequency)", "", false,
       [](const FrameStatistics& s) { return s.spectrum_slope; }},
      {"temperature_p5_c", "temperature p5", "°C", true, [](const FrameStatistics& s) { return s.p5_c; }},
      {"temperature_p50_c", "temperature median", "°C", true, [](const FrameStatistics& s) { return s.p50_c; }},
      {"temperature_p95_c", "temperature p95", "°C", true, [](const FrameStatistics& s) { return s.p95_c; }},
      {"temperature_spread_k", "temperature spread (p95 - p5)", "K", true,
       [](const FrameStatistics& s) { return s.spread_k; }},
      {"wall_residual_k", "wall high-pass residual", "K", true,
       [](const FrameStatistics& s) { return s.wall_residual_k; }},
      {"wall_residual_wall_views_k", "wall high-pass residual, wall-dominated views", "K", true,
       [](const FrameStatistics& s) { return s.wall_dominated ? s.wall_residual_k : NAN; }},
      {"wall_share", "share of pixels within 1.5 K of the median", "", true,
       [](const FrameStatistics& s) { return s.wall_share; }},
      {"flat_noise_k", "flat-region noise (flattest 10 % of 16-px blocks, native size)", "K", true,
       [](const FrameStatistics& s) { return s.flat_noise_k; }},
      {"flat_noise_lag1", "flat-region noise, lag-1 correlation (native size)", "", false,
       [](const FrameStatistics& s) { return s.flat_noise_lag1; }},
  };
  return kList;
}

}  // namespace hoilcd
