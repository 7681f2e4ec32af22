#include "hoilcd/bench/realism/frame_statistics.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

namespace hoilcd {
namespace {

constexpr int kW = kStatisticsWidthPx, kH = kStatisticsHeightPx;

cv::Mat Checkerboard(int square_px) {
  cv::Mat image(kH, kW, CV_8U);
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) image.at<uint8_t>(y, x) = ((x / square_px + y / square_px) % 2) ? 255 : 0;
  }
  return image;
}

cv::Mat Step(int low, int high) {
  cv::Mat image(kH, kW, CV_8U, cv::Scalar(low));
  image(cv::Rect(kW / 2, 0, kW / 2, kH)) = high;
  return image;
}

// A Gaussian field whose power spectrum is proportional to f^-exponent: white noise filtered by
// f^(-exponent/2) in the frequency domain (mean zero), `width` x `height`.
cv::Mat PowerLawField(double exponent, unsigned seed, int width = kW, int height = kH) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  cv::Mat noise(height, width, CV_64F);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) noise.at<double>(y, x) = normal(rng);
  cv::Mat spectrum;
  cv::dft(noise, spectrum, cv::DFT_COMPLEX_OUTPUT);
  for (int y = 0; y < height; ++y) {
    const double fy = static_cast<double>(y <= height / 2 ? y : y - height) / height;
    for (int x = 0; x < width; ++x) {
      const double fx = static_cast<double>(x <= width / 2 ? x : x - width) / width;
      const double f = std::hypot(fx, fy);
      spectrum.at<cv::Vec2d>(y, x) *= f > 0 ? std::pow(f, -exponent / 2) : 0.0;
    }
  }
  cv::Mat field;
  cv::dft(spectrum, field, cv::DFT_INVERSE | cv::DFT_REAL_OUTPUT | cv::DFT_SCALE);
  return field;
}

cv::Mat Noise(double mean, double sigma, unsigned seed, int width = kW, int height = kH) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(mean, sigma);
  cv::Mat t(height, width, CV_32F);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) t.at<float>(y, x) = static_cast<float>(normal(rng));
  return t;
}

TEST(FrameStatistics, CheckerboardHasOneShiTomasiCornerPerInnerCrossing) {
  // 32-px squares: 7 x 5 inner crossings, all further than the 4-px border from the edge.
  const cv::Mat board = Checkerboard(32);
  EXPECT_EQ(ShiTomasiCorners(StretchedFrame(board)), 35);
  EXPECT_EQ(SlcdCorners(StretchedFrame(board)), 35);
}

TEST(FrameStatistics, FlatFrameHasNoCornersEdgesOrEntropy) {
  const cv::Mat flat(kH, kW, CV_32F, cv::Scalar(22.0f));
  const FrameStatistics s = MeasureTemperatureFrame(flat);
  EXPECT_EQ(s.shi_tomasi_corners, 0);
  EXPECT_EQ(s.fast_corners, 0);
  EXPECT_EQ(s.strong_edge_fraction, 0);
  EXPECT_EQ(s.entropy_bits, 0);
  EXPECT_TRUE(std::isnan(s.spectrum_slope));
  EXPECT_TRUE(s.blank);
  EXPECT_NEAR(s.wall_residual_k, 0, 1e-6);
}

TEST(FrameStatistics, StepImageEdgeFractionIsTheTwoColumnsBesideTheStep) {
  // A step of h grey levels gives the columns on both sides a Sobel magnitude of 4h, i.e. h/2 per
  // pixel: strong (> 8) from a step of 17 levels, not at 16.
  EXPECT_DOUBLE_EQ(StrongEdgeFraction(Step(0, 255)), 2.0 / kW);
  EXPECT_DOUBLE_EQ(StrongEdgeFraction(Step(100, 117)), 2.0 / kW);
  EXPECT_DOUBLE_EQ(StrongEdgeFraction(Step(100, 116)), 0.0);
}

TEST(FrameStatistics, EntropyOfTwoEqualHalvesIsOneBitAndOfEveryLevelEightBits) {
  EXPECT_DOUBLE_EQ(EntropyBits(Step(0, 255)), 1.0);
  cv::Mat ramp(kH, kW, CV_8U);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) ramp.at<uint8_t>(y, x) = static_cast<uint8_t>(x);
  EXPECT_DOUBLE_EQ(EntropyBits(ramp), 8.0);
}

TEST(FrameStatistics, SpectrumSlopeOfAPowerLawFieldIsItsExponent) {
  for (const double exponent : {2.0, 2.5, 3.0, 3.5}) {
    const double slope = SpectrumSlope(StretchedFrame(PowerLawField(exponent, 7)));
    EXPECT_NEAR(slope, -exponent, 0.1) << "exponent " << exponent;
  }
  // White noise: a flat spectrum.
  EXPECT_NEAR(SpectrumSlope(StretchedFrame(Noise(0, 1, 3))), 0.0, 0.1);
}

TEST(FrameStatistics, SpectrumSlopeIsItsExponentAtOddAndNonFourByThreeSizes) {
  // Frequencies in cycles per pixel along each axis: rings that no frequency falls in (the x and y
  // steps are 1/width and 1/height, coarser than the 1/256 rings) are left out of the fit.
  for (const cv::Size size : {cv::Size(180, 180), cv::Size(160, 120), cv::Size(181, 143), cv::Size(320, 240)}) {
    for (const double exponent : {2.0, 3.0}) {
      const double slope = SpectrumSlope(NativeStretchedFrame(PowerLawField(exponent, 7, size.width, size.height)));
      EXPECT_NEAR(slope, -exponent, 0.15) << size << " exponent " << exponent;
    }
  }
}

TEST(FrameStatistics, SmallFrameSlopeIsTakenAtNativeSizeNotUpsampled) {
  // Fine structure at the FLIR E40's 160 x 120: noise correlated over about a pixel, as a camera
  // that filters its frames gives it. Upsampling to 256 x 192 spreads each native pixel over 1.6
  // and moves that power below 1/4 cycles per output pixel, steepening the slope.
  cv::Mat small = Noise(22.0, 0.1, 9, 160, 120);
  cv::GaussianBlur(small, small, cv::Size(0, 0), 0.9);
  const double native = SpectrumSlope(NativeStretchedFrame(small));
  const double upsampled = SpectrumSlope(StretchedFrame(small));
  EXPECT_EQ(NativeStretchedFrame(small).size(), cv::Size(160, 120));
  EXPECT_GT(native - upsampled, 0.5) << native << " vs upsampled " << upsampled;
  const FrameStatistics s = MeasureTemperatureFrame(small);
  EXPECT_DOUBLE_EQ(s.spectrum_slope, native);
  EXPECT_EQ(s.width_px, 160);
  EXPECT_EQ(s.height_px, 120);
  EXPECT_DOUBLE_EQ(MeasureGreyFrame(NativeStretchedFrame(small)).spectrum_slope, native);
  // The other image statistics stay on the 256 x 192 frame.
  EXPECT_EQ(s.shi_tomasi_corners, ShiTomasiCorners(StretchedFrame(small)));
  EXPECT_EQ(s.strong_edge_fraction, StrongEdgeFraction(StretchedFrame(small)));
  // Shorter in one dimension is enough: 320 x 180 is measured natively too.
  const cv::Mat wide = PowerLawField(2.0, 9, 320, 180);
  EXPECT_DOUBLE_EQ(MeasureTemperatureFrame(wide).spectrum_slope, SpectrumSlope(NativeStretchedFrame(wide)));
  EXPECT_EQ(SpectrumFrame(wide).size(), cv::Size(320, 180));
}

TEST(FrameStatistics, FrameAtLeastStatisticsSizeIsResizedForTheSlope) {
  const cv::Mat big = PowerLawField(2.5, 4, 320, 240);
  const FrameStatistics s = MeasureTemperatureFrame(big);
  EXPECT_DOUBLE_EQ(s.spectrum_slope, SpectrumSlope(StretchedFrame(big)));
  EXPECT_EQ(SpectrumFrame(big).size(), cv::Size(kW, kH));
  EXPECT_EQ(s.width_px, 320);
  EXPECT_EQ(s.height_px, 240);
  EXPECT_FALSE(SmallerThanStatisticsSize(cv::Size(kW, kH)));
  EXPECT_TRUE(SmallerThanStatisticsSize(cv::Size(kW - 1, kH)));
  EXPECT_TRUE(SmallerThanStatisticsSize(cv::Size(kW, kH - 1)));
}

TEST(FrameStatistics, FlatNoiseIsMeasuredAtNativeSizeAndInKelvinOnlyForTemperatures) {
  const cv::Mat t = Noise(22.0, 0.04, 12, 160, 120);
  const FrameStatistics s = MeasureTemperatureFrame(t);
  EXPECT_NEAR(s.flat_noise_k, 0.04, 0.005);  // not smoothed by a resize to 256 x 192
  EXPECT_LT(std::fabs(s.flat_noise_lag1), 0.05);
  cv::Mat grey;
  t.convertTo(grey, CV_8U, 1000.0, -21872.0);  // 1 grey level per mK, 22 °C at 128
  const FrameStatistics g = MeasureGreyFrame(grey);
  EXPECT_TRUE(std::isnan(g.flat_noise_k));
  EXPECT_LT(std::fabs(g.flat_noise_lag1), 0.05);
}

TEST(FrameStatistics, StretchMapsFirstAndNinetyNinthPercentileToBlackAndWhite) {
  cv::Mat ramp(kH, kW, CV_32F);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) ramp.at<float>(y, x) = static_cast<float>(20.0 + 10.0 * (y * kW + x) / (kW * kH - 1));
  const cv::Mat u8 = StretchedFrame(ramp);
  EXPECT_EQ(u8.type(), CV_8U);
  double lo = 0, hi = 0;
  cv::minMaxLoc(u8, &lo, &hi);
  EXPECT_EQ(lo, 0);
  EXPECT_EQ(hi, 255);
  EXPECT_EQ(u8.at<uint8_t>(kH / 2, kW / 2), 128);
  // Any size is resized to 256 x 192.
  cv::Mat big;
  cv::resize(ramp, big, cv::Size(640, 480));
  EXPECT_EQ(StretchedFrame(big).size(), cv::Size(kW, kH));
}

TEST(FrameStatistics, MedianFilterMatchesTheSortedWindow) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> centikelvin(2000, 2600);
  cv::Mat t(30, 40, CV_32F);
  for (int y = 0; y < t.rows; ++y)
    for (int x = 0; x < t.cols; ++x) t.at<float>(y, x) = static_cast<float>(centikelvin(rng) / 100.0);
  const cv::Mat m = MedianFilter15(t);
  for (int y = 0; y < t.rows; ++y) {
    for (int x = 0; x < t.cols; ++x) {
      std::vector<float> window;
      for (int dy = -7; dy <= 7; ++dy)
        for (int dx = -7; dx <= 7; ++dx)
          window.push_back(t.at<float>(std::clamp(y + dy, 0, t.rows - 1), std::clamp(x + dx, 0, t.cols - 1)));
      std::nth_element(window.begin(), window.begin() + 112, window.end());
      ASSERT_NEAR(m.at<float>(y, x), window[112], 1e-4) << y << "," << x;
    }
  }
}

TEST(FrameStatistics, WallResidualOfWhiteNoiseIsItsStdAndIgnoresHotObjects) {
  cv::Mat t = Noise(22.0, 0.1, 11);
  // The median of 225 samples scatters by sqrt(pi/2) * 0.1 / 15 = 0.008 K: the residual is ~0.1.
  EXPECT_NEAR(WallResidualK(t), 0.1, 0.005);
  double share = 0;
  EXPECT_NEAR(WallResidualK(t, &share), 0.1, 0.005);
  EXPECT_EQ(share, 1.0);
  t(cv::Rect(10, 10, 60, 60)) = 34.0f;  // a person: outside the +-1.5 K band
  EXPECT_NEAR(WallResidualK(t, &share), 0.1, 0.006);
  EXPECT_DOUBLE_EQ(share, 1.0 - 3600.0 / (kW * kH));
  const FrameStatistics s = MeasureTemperatureFrame(t);
  EXPECT_TRUE(s.wall_dominated);  // 93 % of the pixels are wall
  t(cv::Rect(0, 0, kW, kH / 4)) = 34.0f;
  EXPECT_FALSE(MeasureTemperatureFrame(t).wall_dominated);
}

TEST(FrameStatistics, BlankRuleIsASpreadUnderTwoKelvin) {
  const auto ramp = [](double span_k) {
    cv::Mat t(kH, kW, CV_32F);
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) t.at<float>(y, x) = static_cast<float>(22.0 + span_k * x / (kW - 1));
    return t;
  };
  // 256 columns of 192 pixels: p5 falls in column 12, p95 in column 243, so p95 - p5 = 231/255 of the span.
  const FrameStatistics narrow = MeasureTemperatureFrame(ramp(2.0));
  EXPECT_NEAR(narrow.spread_k, 2.0 * 231 / 255, 1e-5);
  EXPECT_TRUE(narrow.blank);
  const FrameStatistics wide = MeasureTemperatureFrame(ramp(2.5));
  EXPECT_NEAR(wide.spread_k, 2.5 * 231 / 255, 1e-5);
  EXPECT_FALSE(wide.blank);
  EXPECT_NEAR(wide.p50_c, 22.0 + 2.5 * 127.5 / 255, 1e-5);
  // Grey frames have no temperatures: never blank, temperature figures NaN.
  const FrameStatistics grey = MeasureGreyFrame(Step(0, 255));
  EXPECT_FALSE(grey.radiometric);
  EXPECT_FALSE(grey.blank);
  EXPECT_TRUE(std::isnan(grey.spread_k));
  EXPECT_TRUE(std::isnan(grey.wall_residual_k));
}

TEST(FrameStatistics, TemporalNoiseOfTwoNoisyFramesIsTheirNoise) {
  const cv::Mat a = Noise(22.0, 0.05, 1), b = Noise(22.0, 0.05, 2);
  EXPECT_NEAR(TemporalNoiseK(a, b), 0.05, 0.002);
  cv::Mat moved = b.clone();
  moved(cv::Rect(0, 0, 40, 40)) = 34.0f;  // someone walked in: robust to it
  EXPECT_NEAR(TemporalNoiseK(a, moved), 0.05, 0.004);
}

TEST(FrameStatistics, EveryStatisticHasAKeyAndAValue) {
  const FrameStatistics s = MeasureTemperatureFrame(Noise(22.0, 1.0, 4));
  for (const StatisticInfo& info : FrameStatisticList()) {
    EXPECT_FALSE(info.key.empty());
    EXPECT_TRUE(std::isfinite(info.value(s))) << info.key;
  }
}

}  // namespace
}  // namespace hoilcd
