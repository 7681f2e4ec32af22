#include "hoilcd/bench/realism/flat_noise.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

namespace hoilcd {
namespace {

constexpr double kSigmaK = 0.04;

// A smooth quadratic temperature ramp, 21..25 °C over a 256 x 192 frame.
cv::Mat QuadraticRamp(int width, int height) {
  cv::Mat t(height, width, CV_64F);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double u = static_cast<double>(x) / width, v = static_cast<double>(y) / height;
      t.at<double>(y, x) = 21.0 + 2.0 * u + 1.0 * v + 0.6 * u * u - 0.4 * v * v + 0.3 * u * v;
    }
  }
  return t;
}

cv::Mat WhiteNoise(int width, int height, double sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, sigma);
  cv::Mat n(height, width, CV_64F);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) n.at<double>(y, x) = normal(rng);
  return n;
}

cv::Mat AsFloat32(const cv::Mat& f64) {
  cv::Mat f;
  f64.convertTo(f, CV_32F);
  return f;
}

TEST(FlatNoise, WhiteNoiseOnAQuadraticRampGivesItsSigmaAndNoCorrelation) {
  const cv::Mat t = AsFloat32(QuadraticRamp(256, 192) + WhiteNoise(256, 192, kSigmaK, 1));
  const FlatNoise n = MeasureFlatNoise(t);
  EXPECT_EQ(n.blocks, 19);  // 16 x 12 blocks, the flattest tenth
  // The quadratic leaves 250 of 256 degrees of freedom, and the flattest tenth of the blocks sit
  // some 1.6 standard errors (4.5 % each) below the rest: about 0.037 K.
  EXPECT_NEAR(n.std, kSigmaK, 0.005);
  EXPECT_LT(n.std, kSigmaK);
  EXPECT_LT(std::fabs(n.lag1), 0.05);
  EXPECT_LT(std::fabs(n.lag1_x), 0.05);
  EXPECT_LT(std::fabs(n.lag1_y), 0.05);
  EXPECT_DOUBLE_EQ(n.lag1, (n.lag1_x + n.lag1_y) / 2);
}

TEST(FlatNoise, GaussianBlurredNoiseIsStronglyCorrelated) {
  cv::Mat noise = WhiteNoise(256, 192, kSigmaK, 1);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), 0.9, 0.9, cv::BORDER_REFLECT);
  const FlatNoise n = MeasureFlatNoise(AsFloat32(QuadraticRamp(256, 192) + noise));
  // Gaussian-filtered white noise correlates as exp(-d² / 4σ²): 0.73 at one pixel.
  EXPECT_GT(n.lag1, 0.5);
  EXPECT_GT(n.lag1_x, 0.5);
  EXPECT_GT(n.lag1_y, 0.5);
  EXPECT_LT(n.std, kSigmaK / 2);  // the filter removes most of the noise's power
}

TEST(FlatNoise, TheQuadraticIsRemovedExactly) {
  const FlatNoise n = MeasureFlatNoise(QuadraticRamp(64, 48) * 100.0);
  EXPECT_NEAR(n.std, 0.0, 1e-9);
}

TEST(FlatNoise, SmallestShareIsOneBlockAndPartialBlocksAreLeftOut) {
  // 40 x 20: two whole blocks; a tenth of them rounds to none, so one is kept.
  const FlatNoise n = MeasureFlatNoise(AsFloat32(WhiteNoise(40, 20, kSigmaK, 2)));
  EXPECT_EQ(n.blocks, 1);
  EXPECT_TRUE(std::isfinite(n.std));
  // Smaller than one block: nothing to measure.
  const FlatNoise none = MeasureFlatNoise(AsFloat32(WhiteNoise(15, 40, kSigmaK, 2)));
  EXPECT_EQ(none.blocks, 0);
  EXPECT_TRUE(std::isnan(none.std));
  EXPECT_TRUE(std::isnan(none.lag1));
}

TEST(FlatNoise, FlatFrameHasNoCorrelation) {
  const FlatNoise n = MeasureFlatNoise(cv::Mat(48, 64, CV_8U, cv::Scalar(90)));
  EXPECT_EQ(n.std, 0.0);
  EXPECT_TRUE(std::isnan(n.lag1));
}

TEST(FlatNoise, KeepsTheFlattestBlocks) {
  // Half the frame carries ten times the noise: the flattest tenth all lie in the quiet half.
  cv::Mat noise = WhiteNoise(320, 160, kSigmaK, 3);
  noise(cv::Rect(0, 0, 160, 160)) *= 10.0;
  const FlatNoise n = MeasureFlatNoise(AsFloat32(noise));
  EXPECT_EQ(n.blocks, 20);
  EXPECT_NEAR(n.std, kSigmaK, 0.005);
}

}  // namespace
}  // namespace hoilcd
