#include "hoilcd/sim/sensor/optics.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "hoilcd/sim/sensor/sensor.h"

namespace hoilcd {
namespace {

// The paper's camera: 12 µm pixels behind an f/1.1 lens, 8–14 µm, weighed at 300 K.
PixelResponse Pocket2() { return {1.1, 12.0, 1.0, 0.0, 8.0, 14.0, 300.0}; }

// A DCT-II basis image, cos(π·u·(x + ½)/W)·cos(π·v·(y + ½)/H): the pattern of frequency
// (u/2W, v/2H) cycles/px, symmetric about the borders as the filter mirrors them.
cv::Mat Basis(int width, int height, int u, int v, float mean) {
  cv::Mat image(height, width, CV_32F);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      image.at<float>(y, x) =
          mean + static_cast<float>(std::cos(M_PI * u * (x + 0.5) / width) * std::cos(M_PI * v * (y + 0.5) / height));
  return image;
}

TEST(PixelResponse, CircularApertureMtfHasItsClosedFormValues) {
  EXPECT_DOUBLE_EQ(CircularApertureMtf(0.0), 1.0);
  EXPECT_NEAR(CircularApertureMtf(0.5), (2.0 / M_PI) * (std::acos(0.5) - 0.5 * std::sqrt(0.75)), 1e-15);
  EXPECT_NEAR(CircularApertureMtf(0.5), 0.391002, 1e-6);
  EXPECT_EQ(CircularApertureMtf(1.0), 0.0);
  EXPECT_EQ(CircularApertureMtf(1.7), 0.0);
  EXPECT_EQ(CircularApertureMtf(-0.3), CircularApertureMtf(0.3));
  for (double nu = 0.0; nu < 1.0; nu += 0.05) EXPECT_GT(CircularApertureMtf(nu), CircularApertureMtf(nu + 0.05));
}

TEST(PixelResponse, MtfIsDiffractionTimesPixelAreaAtTheCameraFigures) {
  const PixelResponse r = Pocket2();
  EXPECT_DOUBLE_EQ(PixelResponseMtf(r, 0.0, 0.0), 1.0);
  // Along x, at one wavelength: the pixel's sinc times the aperture's MTF at ν = f·λ·N/pitch.
  PixelResponse mono = r;
  mono.lambda_min_um = 9.999;
  mono.lambda_max_um = 10.001;
  const double sinc = std::sin(M_PI * 0.25) / (M_PI * 0.25);
  EXPECT_NEAR(PixelResponseMtf(mono, 0.25, 0.0), sinc * CircularApertureMtf(0.25 * 10.0 * 1.1 / 12.0), 1e-4);
  // Over the band, weighted by the 300 K spectrum: 0.820 at 0.125 cycles/px, 0.618 at 0.25.
  EXPECT_NEAR(PixelResponseMtf(r, 0.125, 0.0), 0.820, 0.002);
  EXPECT_NEAR(PixelResponseMtf(r, 0.25, 0.0), 0.618, 0.002);
  // Diffraction is round, the pixel square: the diagonal differs from the axis at the same |f|.
  const double d = 0.25 / std::sqrt(2.0);
  EXPECT_GT(PixelResponseMtf(r, d, d), PixelResponseMtf(r, 0.25, 0.0));
  // Beyond the shortest wavelength's cutoff, pitch/(λN) = 1.36 cycles/px at 8 µm, nothing passes.
  EXPECT_NE(PixelResponseMtf(r, 1.3, 0.0), 0.0);  // negative: past 1 cycle/px the pixel's sinc reverses contrast
  EXPECT_EQ(PixelResponseMtf(r, 1.4, 0.0), 0.0);
}

TEST(PixelResponse, EachParameterMovesTheMtfTheWayPhysicsSays) {
  const double base = PixelResponseMtf(Pocket2(), 0.2, 0.1);
  PixelResponse slower = Pocket2();
  slower.f_number = 2.0;
  EXPECT_LT(PixelResponseMtf(slower, 0.2, 0.1), base);
  PixelResponse larger = Pocket2();
  larger.pixel_pitch_um = 17.0;  // the same lens, larger pixels: diffraction is smaller in pixels
  EXPECT_GT(PixelResponseMtf(larger, 0.2, 0.1), base);
  PixelResponse smaller_absorber = Pocket2();
  smaller_absorber.fill_factor = 0.64;
  EXPECT_GT(PixelResponseMtf(smaller_absorber, 0.2, 0.1), base);
  PixelResponse aberrated = Pocket2();
  aberrated.aberration_sigma_px = 0.5;
  EXPECT_NEAR(PixelResponseMtf(aberrated, 0.2, 0.1), base * std::exp(-2.0 * M_PI * M_PI * 0.25 * 0.05), 1e-12);
  PixelResponse hotter = Pocket2();
  hotter.band_temperature_k = 600.0;  // the spectrum shifts to shorter waves: less diffraction
  EXPECT_GT(PixelResponseMtf(hotter, 0.2, 0.1), base);
}

TEST(PixelResponse, FilterScalesEachFrequencyByTheMtfAndKeepsTheMean) {
  for (const double f_number : {1.0, 1.1, 1.3, 4.0}) {
    SCOPED_TRACE(f_number);
    PixelResponse r = Pocket2();
    r.f_number = f_number;
    const PixelResponseFilter filter(r, 64, 48);
    for (const auto& [u, v] : std::vector<std::pair<int, int>>{{0, 0}, {5, 0}, {0, 7}, {16, 12}, {40, 30}, {63, 47}}) {
      SCOPED_TRACE(testing::Message() << u << "," << v);
      const double mtf = PixelResponseMtf(r, u / 128.0, v / 96.0);
      EXPECT_NEAR(filter.GainAt(u, v), mtf, 1e-6);
      const cv::Mat in = Basis(64, 48, u, v, 30.0f);
      cv::Mat out;
      filter.Apply(in, &out);
      ASSERT_EQ(out.size(), in.size());
      ASSERT_EQ(out.type(), CV_32F);
      double worst = 0.0;
      for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x) {
          const double expected = 30.0 + (u == 0 && v == 0 ? 1.0 : mtf) * (in.at<float>(y, x) - 30.0);
          worst = std::max(worst, std::abs(out.at<float>(y, x) - expected));
        }
      EXPECT_LT(worst, 2e-5);
    }
  }
}

TEST(PixelResponse, FilterBlursAnEdgeAsDiffractionAndPixelAreaDo) {
  // A vertical edge from 20 to 40 across a 256 x 192 frame: the response falls off over about
  // two pixels, symmetric about the edge, without overshoot beyond the MTF's own ringing.
  const int w = 256, h = 192;
  cv::Mat edge(h, w, CV_32F, cv::Scalar(20.0f));
  edge(cv::Rect(w / 2, 0, w / 2, h)).setTo(40.0f);
  const PixelResponseFilter filter(Pocket2(), w, h);
  cv::Mat out;
  filter.Apply(edge, &out);
  const float* row = out.ptr<float>(h / 2);
  // Pixels w/2 − 1 and w/2 straddle the edge: symmetric about 30.
  EXPECT_NEAR(row[w / 2 - 1] + row[w / 2], 60.0, 1e-3);
  EXPECT_GT(row[w / 2 - 1], 21.0);  // blurred: the dark side takes some of the bright
  EXPECT_LT(row[w / 2 - 1], 28.0);
  EXPECT_NEAR(row[w / 2 - 6], 20.0, 0.3);  // five pixels away little is left
  EXPECT_NEAR(row[10], 20.0, 0.05);
  EXPECT_NEAR(row[w - 10], 40.0, 0.05);
  // A uniform frame stays itself, and the output does not depend on the frame's rows.
  EXPECT_EQ(out.row(3).size(), out.row(100).size());
  EXPECT_LT(cv::norm(out.row(3), out.row(100), cv::NORM_INF), 1e-4);
  cv::Mat uniform(h, w, CV_32F, cv::Scalar(38.125f)), flat;
  filter.Apply(uniform, &flat);
  EXPECT_LT(cv::norm(flat, uniform, cv::NORM_INF), 1e-4);
}

TEST(PixelResponse, AnOddSizedFrameIsFilteredAsItsMirror) {
  // 65 x 49: the filter mirrors one more column and row; a uniform frame stays uniform and a
  // symmetric pattern stays symmetric.
  const PixelResponseFilter filter(Pocket2(), 65, 49);
  cv::Mat spot(49, 65, CV_32F, cv::Scalar(25.0f)), out;
  spot.at<float>(24, 32) = 35.0f;
  filter.Apply(spot, &out);
  ASSERT_EQ(out.size(), spot.size());
  EXPECT_LT(out.at<float>(24, 32), 35.0f);
  EXPECT_GT(out.at<float>(24, 32), 28.0f);
  EXPECT_NEAR(out.at<float>(24, 31), out.at<float>(24, 33), 1e-4);
  EXPECT_NEAR(out.at<float>(23, 32), out.at<float>(25, 32), 1e-4);
  // Round diffraction, square pixel: the axes alike (to the grids' sampling, 66 and 50 wide).
  EXPECT_NEAR(out.at<float>(23, 32), out.at<float>(24, 31), 1e-3);
  EXPECT_NEAR(cv::sum(out)[0], cv::sum(spot)[0], 1e-2);  // energy kept
}

TEST(PixelResponse, FilterGivesTheSameBytesAtAnyThreadCount) {
  cv::Mat noise(192, 256, CV_32F);
  cv::RNG rng(7);  // a fixed pattern for the input only
  rng.fill(noise, cv::RNG::UNIFORM, 20.0f, 40.0f);
  const PixelResponseFilter filter(Pocket2(), 256, 192);
  cv::Mat one, two, five;
  filter.Apply(noise, &one, 1);
  filter.Apply(noise, &two, 2);
  filter.Apply(noise, &five, 5);
  EXPECT_EQ(std::memcmp(one.data, two.data, one.total() * sizeof(float)), 0);
  EXPECT_EQ(std::memcmp(one.data, five.data, one.total() * sizeof(float)), 0);
}

TEST(PixelResponse, NonsenseParametersAreRefused) {
  PixelResponse r = Pocket2();
  r.fill_factor = 0.0;
  EXPECT_THROW(PixelResponseFilter(r, 8, 8), std::exception);
  r = Pocket2();
  r.f_number = -1.0;
  EXPECT_THROW(PixelResponseMtf(r, 0.1, 0.0), std::exception);
  r = Pocket2();
  r.lambda_max_um = r.lambda_min_um;
  EXPECT_THROW(PixelResponseFilter(r, 8, 8), std::exception);
  EXPECT_THROW(PixelResponseFilter(Pocket2(), 0, 8), std::exception);
  const PixelResponseFilter filter(Pocket2(), 8, 8);
  cv::Mat wrong(8, 9, CV_32F, cv::Scalar(1.0f)), out;
  EXPECT_THROW(filter.Apply(wrong, &out), std::exception);
}

TEST(PixelResponse, SensorOptionsAndTheBandMakeTheResponse) {
  const BandRadianceTable table(7.5, 13.5);
  SensorOptions options;
  options.f_number = 1.3;
  options.pixel_pitch_um = 17.0;
  options.pixel_fill_factor = 0.8;
  options.aberration_sigma_px = 0.2;
  options.reference_temperature_c = 30.0;
  const PixelResponse r = PixelResponseOf(options, table);
  EXPECT_EQ(r.f_number, 1.3);
  EXPECT_EQ(r.pixel_pitch_um, 17.0);
  EXPECT_EQ(r.fill_factor, 0.8);
  EXPECT_EQ(r.aberration_sigma_px, 0.2);
  EXPECT_EQ(r.lambda_min_um, 7.5);
  EXPECT_EQ(r.lambda_max_um, 13.5);
  EXPECT_DOUBLE_EQ(r.band_temperature_k, 303.15);
}

}  // namespace
}  // namespace hoilcd
