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
// f^(-exponent/2) in the frequency domain (mean zero).
cv::Mat PowerLawField(double exponent, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  cv::Mat noise(kH, kW, CV_64F);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) noise.at<double>(y, x) = normal(rng);
  cv::Mat spectrum;
  cv::dft(noise, spectrum, cv::DFT_COMPLEX_OUTPUT);
  for (int y = 0; y < kH; ++y) {
    const double fy = static_cast<double>(y <= kH / 2 ? y : y - kH) / kH;
    for (int x = 0; x < kW; ++x) {
      const double fx = static_cast<double>(x <= kW / 2 ? x : x - kW) / kW;
      const double f = std::hypot(fx, fy);
      spectrum.at<cv::Vec2d>(y, x) *= f > 0 ? std::pow(f, -exponent / 2) : 0.0;
    }
  }
  cv::Mat field;
  cv::dft(spectrum, field, cv::DFT_INVERSE | cv::DFT_REAL_OUTPUT | cv::DFT_SCALE);
  return field;
}

cv::Mat Noise(double mean, double sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(mean, sigma);
  cv::Mat t(kH, kW, CV_32F);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) t.at<float>(y, x) = static_cast<float>(normal(rng));
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
