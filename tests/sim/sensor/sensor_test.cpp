#include "hoilcd/sim/sensor/sensor.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "hoilcd/core/dataset/frame_encoding.h"

namespace hoilcd {
namespace {

constexpr int kWidth = 256;
constexpr int kHeight = 192;
constexpr double kFrameRateHz = 25.0;

SensorOptions AllOff() {
  SensorOptions options;
  options.optics_blur = false;
  options.temporal_noise = false;
  options.fixed_pattern = false;
  options.drift = false;
  options.time_constant = false;
  options.quantisation = false;
  options.lens_shading = false;
  options.ffc_freeze = false;
  return options;
}

cv::Mat Uniform(const BandRadianceTable& table, float temperature_c) {
  return cv::Mat(kHeight, kWidth, CV_32F, cv::Scalar(table.RadianceFromCelsius(temperature_c)));
}

// A 22 °C room with a 34 °C block sliding 3 px right per frame.
cv::Mat MovingScene(const BandRadianceTable& table, int frame) {
  cv::Mat radiance = Uniform(table, 22.0f);
  radiance(cv::Rect(20 + 3 * frame, 60, 40, 70)).setTo(table.RadianceFromCelsius(34.0f));
  return radiance;
}

bool SameBytes(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0.0;
}

// Mean over pixels of the per-pixel temporal variance, as a standard deviation.
double TemporalStd(const std::vector<cv::Mat>& frames) {
  cv::Mat sum = cv::Mat::zeros(kHeight, kWidth, CV_64F), sum2 = sum.clone();
  for (const cv::Mat& frame : frames) {
    cv::Mat f64;
    frame.convertTo(f64, CV_64F);
    sum += f64;
    sum2 += f64.mul(f64);
  }
  const double n = static_cast<double>(frames.size());
  cv::Mat variance = (sum2 - sum.mul(sum) / n) / (n - 1.0);
  return std::sqrt(cv::mean(variance)[0]);
}

TEST(SensorOptions, DefaultsAreValidAndBadFieldsAreNamed) {
  EXPECT_EQ(SensorOptions().Check(), "");
  SensorOptions options;
  options.netd_k = -0.1;
  EXPECT_NE(options.Check().find("netd_k"), std::string::npos);
  options = SensorOptions();
  options.ffc_interval_s = 0.5;
  EXPECT_NE(options.Check().find("ffc_interval_s"), std::string::npos);
  options = SensorOptions();
  options.emissivity_setting = 0.0;
  EXPECT_NE(options.Check().find("emissivity_setting"), std::string::npos);
  options = SensorOptions();
  options.display_max_c = options.display_min_c;
  EXPECT_NE(options.Check().find("display_max_c"), std::string::npos);
  options = SensorOptions();
  options.time_constant_s = 0.0;
  EXPECT_NE(options.Check().find("time_constant_s"), std::string::npos);
}

TEST(SensorModel, IsothermalSceneWithEffectsOffReads25CExactly) {
  const BandRadianceTable table;
  SensorModel model(AllOff(), kWidth, kHeight, kFrameRateHz, 1, &table);
  const cv::Mat radiance = Uniform(table, 25.0f);
  const cv::Mat temperature = model.Apply(0, radiance);
  double min_c = 0, max_c = 0;
  cv::minMaxLoc(temperature, &min_c, &max_c);
  EXPECT_NEAR(min_c, 25.0, 1e-4);
  EXPECT_NEAR(max_c, 25.0, 1e-4);
  EXPECT_TRUE(SameBytes(temperature, model.IdealTemperature(radiance)));
  EXPECT_EQ(cv::countNonZero(ToCentikelvin16(temperature) != 29815), 0);
}

TEST(SensorModel, DeterministicEffectsKeepAUniform25CFieldAt25C) {
  const BandRadianceTable table;
  SensorOptions options = AllOff();
  options.optics_blur = true;
  options.time_constant = true;
  options.quantisation = true;
  SensorModel model(options, kWidth, kHeight, kFrameRateHz, 1, &table);
  for (int frame = 0; frame < 3; ++frame) {
    const cv::Mat temperature = model.Apply(frame, Uniform(table, 25.0f));
    EXPECT_EQ(cv::countNonZero(temperature != 25.0f), 0);
  }
}

TEST(SensorModel, TemporalNoiseOfStaticWallIsNetd) {
  const BandRadianceTable table;
  SensorOptions options = AllOff();
  options.temporal_noise = true;
  SensorModel model(options, kWidth, kHeight, kFrameRateHz, 7, &table);
  std::vector<cv::Mat> frames;
  for (int frame = 0; frame < 100; ++frame) frames.push_back(model.Apply(frame, Uniform(table, 22.0f)));
  const double std_k = TemporalStd(frames);
  EXPECT_NEAR(std_k, options.netd_k, 0.2 * options.netd_k);
  // Noise is in the signal domain: at 22 °C it reads NETD·L'(300 K)/L'(295.15 K) ≈ 1.046 NETD.
  EXPECT_NEAR(std_k, model.TemporalNoiseK(22.0), 0.02 * model.TemporalNoiseK(22.0));
  EXPECT_GT(model.TemporalNoiseK(22.0), options.netd_k);
  EXPECT_LT(model.TemporalNoiseK(35.0), options.netd_k);
}

// The in-camera spatial filter (off by default) smooths the noise in space: less of it, and
// neighbours alike (the FLIR E8xt's frames show lag-1 correlations of 0.71); a flat field stays
// flat and the output stays on the quantisation step.
TEST(SensorModel, SpatialFilterCorrelatesAndLowersTheNoiseAndKeepsTheStep) {
  const BandRadianceTable table;
  EXPECT_FALSE(SensorOptions().spatial_filter);
  SensorOptions options = AllOff();
  options.temporal_noise = true;
  SensorOptions filtered = options;
  filtered.spatial_filter = true;
  filtered.quantisation = true;
  SensorModel plain_model(options, kWidth, kHeight, kFrameRateHz, 3, &table);
  SensorModel filtered_model(filtered, kWidth, kHeight, kFrameRateHz, 3, &table);
  std::vector<cv::Mat> plain_frames, filtered_frames;
  for (int frame = 0; frame < 40; ++frame) {
    plain_frames.push_back(plain_model.Apply(frame, Uniform(table, 22.0f)));
    filtered_frames.push_back(filtered_model.Apply(frame, Uniform(table, 22.0f)));
  }
  // A Gaussian of σ passes 1/(2σ√π) of white noise's std: 0.31 at 0.9 px.
  EXPECT_NEAR(TemporalStd(filtered_frames) / TemporalStd(plain_frames), 1.0 / (2.0 * 0.9 * std::sqrt(M_PI)), 0.05);
  auto lag1 = [](const cv::Mat& t) {
    cv::Mat d;
    t.convertTo(d, CV_64F);
    d -= cv::mean(d)[0];
    const cv::Mat a = d(cv::Rect(0, 0, d.cols - 1, d.rows)), b = d(cv::Rect(1, 0, d.cols - 1, d.rows));
    return a.dot(b) / a.dot(a);
  };
  EXPECT_LT(std::abs(lag1(plain_frames[5])), 0.05);
  EXPECT_GT(lag1(filtered_frames[5]), 0.5);
  for (const float v : cv::Mat_<float>(filtered_frames[5])) {
    EXPECT_NEAR(v / 0.01, std::round(v / 0.01), 1e-3);
  }
  filtered.temporal_noise = false;
  SensorModel flat_model(filtered, kWidth, kHeight, kFrameRateHz, 3, &table);
  EXPECT_EQ(cv::countNonZero(flat_model.Apply(0, Uniform(table, 25.0f)) != 25.0f), 0);
}

TEST(SensorModel, TemporalNoiseIsStillNetdWithEveryEffectOn) {
  const BandRadianceTable table;
  SensorModel model(SensorOptions(), kWidth, kHeight, kFrameRateHz, 7, &table);
  ASSERT_TRUE(model.FfcFrames(100).empty());
  std::vector<cv::Mat> frames;
  for (int frame = 0; frame < 100; ++frame) {
    cv::Mat temperature = model.Apply(frame, Uniform(table, 22.0f));
    temperature -= cv::mean(temperature)[0];  // removes the global drift ramp
    frames.push_back(temperature);
  }
  EXPECT_NEAR(TemporalStd(frames), 0.040, 0.2 * 0.040);
}

TEST(SensorModel, FixedPatternIsSameEveryFrameAndDiffersAcrossPixels) {
  const BandRadianceTable table;
  SensorOptions options = AllOff();
  options.fixed_pattern = true;
  SensorModel model(options, kWidth, kHeight, kFrameRateHz, 3, &table);
  const cv::Mat first = model.Apply(0, Uniform(table, 22.0f));
  for (int frame = 1; frame < 5; ++frame) {
    EXPECT_TRUE(SameBytes(model.Apply(frame, Uniform(table, 22.0f)), first));
  }
  // Column stripes: the spread of column means; pixel offsets: the spread around them.
  cv::Mat column_means;
  cv::reduce(first, column_means, 0, cv::REDUCE_AVG);
  cv::Scalar column_mean, column_std;
  cv::meanStdDev(column_means, column_mean, column_std);
  EXPECT_NEAR(column_std[0], options.column_stripe_k, 0.3 * options.column_stripe_k);
  cv::Mat within = first - cv::repeat(column_means, kHeight, 1);
  cv::Scalar within_mean, within_std;
  cv::meanStdDev(within, within_mean, within_std);
  EXPECT_NEAR(within_std[0], options.fpn_offset_k, 0.1 * options.fpn_offset_k);

  SensorModel other_seed(options, kWidth, kHeight, kFrameRateHz, 4, &table);
  EXPECT_FALSE(SameBytes(other_seed.Apply(0, Uniform(table, 22.0f)), first));
}

TEST(SensorModel, GainErrorVanishesAtShutterTemperatureAndGrowsAwayFromIt) {
  const BandRadianceTable table;
  SensorOptions options = AllOff();
  options.fixed_pattern = true;
  options.fpn_offset_k = 0.0;
  options.column_stripe_k = 0.0;
  options.fpn_gain_sigma = 0.01;
  SensorModel model(options, kWidth, kHeight, kFrameRateHz, 3, &table);
  cv::Scalar mean, at_shutter, hot;
  cv::meanStdDev(model.Apply(0, Uniform(table, 25.0f)), mean, at_shutter);
  cv::meanStdDev(model.Apply(1, Uniform(table, 35.0f)), mean, hot);
  EXPECT_LT(at_shutter[0], 1e-4);
  // 1 % gain spread on a 10 K contrast: about 0.1 K.
  EXPECT_NEAR(hot[0], 0.1, 0.02);
}

TEST(SensorModel, QuantisationRoundsAsStdRoundBitForBitAroundZeroCelsius) {
  const BandRadianceTable table;
  SensorOptions options = AllOff();
  options.quantisation = true;
  SensorModel model(options, kWidth, kHeight, kFrameRateHz, 5, &table);
  // −2 °C .. +2 °C in steps far below the 0.01 K quantisation step, so many values fall just
  // beside a rounding boundary and some round to −0.
  cv::Mat radiance(kHeight, kWidth, CV_32F);
  for (int p = 0; p < kWidth * kHeight; ++p) {
    radiance.ptr<float>()[p] = table.RadianceFromCelsius(-2.0f + 4.0f * p / (kWidth * kHeight));
  }
  const cv::Mat ideal = model.IdealTemperature(radiance);
  const cv::Mat quantised = model.Apply(0, radiance);
  int negative_zeros = 0;
  for (int p = 0; p < kWidth * kHeight; ++p) {
    const float expected = static_cast<float>(std::round(ideal.ptr<float>()[p] / 0.01) * 0.01);
    const float got = quantised.ptr<float>()[p];
    ASSERT_EQ(std::memcmp(&expected, &got, sizeof got), 0) << p << ": " << expected << " vs " << got;
    negative_zeros += got == 0.0f && std::signbit(got);
  }
  EXPECT_GT(negative_zeros, 0);
}

TEST(SensorModel, TimeConstantBlendsOneFrameOfAStep) {
  const BandRadianceTable table;
  SensorOptions options = AllOff();
  options.time_constant = true;
  SensorModel model(options, kWidth, kHeight, kFrameRateHz, 1, &table);
  model.Apply(0, Uniform(table, 22.0f));
  const double a = 1.0 - std::exp(-0.040 / options.time_constant_s);
  const double expected_c =
      table.KelvinFromRadiance(a * table.RadianceFromKelvin(305.15) + (1.0 - a) * table.RadianceFromKelvin(295.15)) -
      kZeroCelsiusK;
  EXPECT_NEAR(model.Apply(1, Uniform(table, 32.0f)).at<float>(10, 10), expected_c, 1e-4);
  EXPECT_LT(expected_c, 31.9);
  EXPECT_NEAR(model.Apply(2, Uniform(table, 32.0f)).at<float>(10, 10), 32.0, 1e-4);
}

TEST(SensorModel, DriftRampsBetweenFlatFieldCorrectionsAndResetsAtEach) {
  const BandRadianceTable table;
  SensorOptions options = AllOff();
  options.drift = true;
  options.drift_k_per_min = 2.0;
  options.ffc_interval_s = 2.0;
  SensorModel model(options, kWidth, kHeight, kFrameRateHz, 5, &table);
  EXPECT_EQ(model.FfcFrames(200), (std::vector<int>{50, 100, 150}));
  double largest_k = 0.0;
  for (int ffc : {0, 50, 100, 150}) {
    EXPECT_EQ(model.DriftK(ffc), 0.0);
    // Linear ramp within the interval.
    EXPECT_NEAR(model.DriftK(ffc + 40), 2.0 * model.DriftK(ffc + 20), 1e-12);
    largest_k = std::max(largest_k, std::abs(model.DriftK(ffc + 49)));
  }
  EXPECT_GT(largest_k, 0.01);
  EXPECT_NE(model.DriftK(49), model.DriftK(99));  // a new slope after each FFC

  const cv::Mat radiance = Uniform(table, 22.0f);
  const cv::Mat ideal = model.IdealTemperature(radiance);
  for (int frame = 0; frame < 52; ++frame) {
    const cv::Mat temperature = model.Apply(frame, radiance);
    if (frame == 50) {
      EXPECT_TRUE(SameBytes(temperature, ideal));
    }
    if (frame == 49) {
      EXPECT_NEAR(temperature.at<float>(0, 0) - ideal.at<float>(0, 0),
                  model.DriftK(49) * table.SlopeFromKelvin(300.0) / table.SlopeFromKelvin(295.15), 1e-4);
    }
  }
}

TEST(SensorModel, NoFlatFieldCorrectionWhenIntervalIsZero) {
  const BandRadianceTable table;
  SensorOptions options;
  options.ffc_interval_s = 0.0;
  SensorModel model(options, kWidth, kHeight, kFrameRateHz, 5, &table);
  EXPECT_TRUE(model.FfcFrames(100000).empty());
  EXPECT_NEAR(model.DriftK(2000), 2.0 * model.DriftK(1000), 1e-12);
}

// A FLIR Lepton's automatic FFC (Lepton engineering datasheet 500-0659-00-09, FFC states): every
// 3 min, or sooner when the camera's temperature has changed by 1.5 K since the last FFC.
SensorOptions LeptonFfc() {
  SensorOptions options;
  options.ffc_interval_s = 180.0;
  options.ffc_temperature_delta_k = 1.5;
  return options;
}

// FFC times over 400 s at 8.7 Hz, in seconds (frame / rate).
std::vector<double> FfcTimesOver400s(const SensorOptions& options) {
  const BandRadianceTable table;
  constexpr double kLeptonHz = 8.7;
  const SensorModel model(options, 160, 120, kLeptonHz, 5, &table);
  std::vector<double> times_s;
  for (int frame : model.FfcFrames(static_cast<int>(400 * kLeptonHz))) times_s.push_back(frame / kLeptonHz);
  return times_s;
}

TEST(SensorModel, ALeptonCorrectsEveryThreeMinutesWhenItsHousingWarmsAtTheDefaultRate) {
  SensorOptions options = LeptonFfc();
  ASSERT_EQ(options.housing_warming_k_per_min, 0.5);  // 1.5 K takes 180 s: both triggers agree
  EXPECT_EQ(FfcPeriodS(options), 180.0);
  const std::vector<double> times_s = FfcTimesOver400s(options);
  ASSERT_EQ(times_s.size(), 2u);
  EXPECT_NEAR(times_s[0], 180.0, 0.5 / 8.7);
  EXPECT_NEAR(times_s[1], 360.0, 0.5 / 8.7);
}

TEST(SensorModel, AFasterWarmingHousingTriggersTheFfcByTemperatureBeforeTheInterval) {
  SensorOptions options = LeptonFfc();
  options.housing_warming_k_per_min = 1.0;  // 1.5 K in 90 s
  EXPECT_EQ(FfcPeriodS(options), 90.0);
  const std::vector<double> times_s = FfcTimesOver400s(options);
  ASSERT_EQ(times_s.size(), 4u);
  for (size_t i = 0; i < times_s.size(); ++i) EXPECT_NEAR(times_s[i], 90.0 * (i + 1), 0.5 / 8.7);
  // A slower one leaves the interval in charge; no interval leaves the temperature alone.
  options.housing_warming_k_per_min = 0.25;
  EXPECT_EQ(FfcPeriodS(options), 180.0);
  options.ffc_interval_s = 0;
  EXPECT_EQ(FfcPeriodS(options), 360.0);
  EXPECT_EQ(FfcTimesOver400s(options).size(), 1u);
  // Off (the default), or a housing that does not warm: the interval alone.
  SensorOptions interval_only;
  EXPECT_EQ(interval_only.ffc_temperature_delta_k, 0.0);
  EXPECT_EQ(FfcPeriodS(interval_only), interval_only.ffc_interval_s);
  options = LeptonFfc();
  options.housing_warming_k_per_min = 0;
  EXPECT_EQ(FfcPeriodS(options), 180.0);
}

TEST(SensorModel, ATemperatureTriggerFasterThanOneFfcASecondIsRefused) {
  SensorOptions options = LeptonFfc();
  options.ffc_temperature_delta_k = 0.1;
  options.housing_warming_k_per_min = 10;  // 0.6 s
  EXPECT_EQ(options.Check().rfind("ffc_temperature_delta_k: must give at least 1 s between FFCs", 0), 0u)
      << options.Check();
}

TEST(SensorModel, EmissivitySettingRecoversTheTrueTemperatureOfAGreySurface) {
  const BandRadianceTable table;
  SensorOptions options = AllOff();
  options.emissivity_setting = 0.9;
  options.reflected_temperature_c = 22.0;
  SensorModel model(options, kWidth, kHeight, kFrameRateHz, 1, &table);
  const float radiance = SurfaceRadiance(0.9f, table.RadianceFromCelsius(30.0f), table.RadianceFromCelsius(22.0f));
  const cv::Mat scene(kHeight, kWidth, CV_32F, cv::Scalar(radiance));
  EXPECT_NEAR(model.IdealTemperature(scene).at<float>(0, 0), 30.0f, 1e-3f);
  EXPECT_NEAR(model.Apply(0, scene).at<float>(5, 5), 30.0f, 1e-3f);
}

TEST(SensorModel, SameSeedGivesSameBytesAtAnyThreadCountAndOtherSeedsDiffer) {
  const BandRadianceTable table;
  SensorModel one_thread(SensorOptions(), kWidth, kHeight, kFrameRateHz, 11, &table, 1);
  SensorModel three_threads(SensorOptions(), kWidth, kHeight, kFrameRateHz, 11, &table, 3);
  SensorModel other_seed(SensorOptions(), kWidth, kHeight, kFrameRateHz, 12, &table, 1);
  for (int frame = 0; frame < 5; ++frame) {
    const cv::Mat radiance = MovingScene(table, frame);
    const cv::Mat reference = one_thread.Apply(frame, radiance);
    EXPECT_TRUE(SameBytes(three_threads.Apply(frame, radiance), reference));
    EXPECT_FALSE(SameBytes(other_seed.Apply(frame, radiance), reference));
  }
}

// Mean of a size×size patch of `image` centred on (x, y) (clamped to the image).
double PatchMean(const cv::Mat& image, int x, int y, int size) {
  const int x0 = std::clamp(x - size / 2, 0, image.cols - size);
  const int y0 = std::clamp(y - size / 2, 0, image.rows - size);
  return cv::mean(image(cv::Rect(x0, y0, size, size)))[0];
}

double CornerMinusCentre(const cv::Mat& image, int size) {
  const int w = image.cols - 1, h = image.rows - 1;
  const double corners = (PatchMean(image, 0, 0, size) + PatchMean(image, w, 0, size) + PatchMean(image, 0, h, size) +
                          PatchMean(image, w, h, size)) /
                         4.0;
  return corners - PatchMean(image, w / 2, h / 2, size);
}

TEST(SensorOptions, LensShadingAndFreezeFieldsAreChecked) {
  const std::vector<std::pair<std::string, std::function<void(SensorOptions*)>>> cases = {
      {"housing_warming_k_per_min", [](SensorOptions* o) { o->housing_warming_k_per_min = -1; }},
      {"vignetting_k_per_k", [](SensorOptions* o) { o->vignetting_k_per_k = 9; }},
      {"narcissus_k_per_k", [](SensorOptions* o) { o->narcissus_k_per_k = -9; }},
      {"narcissus_sigma", [](SensorOptions* o) { o->narcissus_sigma = 0; }},
      {"ffc_freeze_s", [](SensorOptions* o) { o->ffc_freeze_s = -0.5; }},
  };
  for (const auto& [field, spoil] : cases) {
    SensorOptions options;
    spoil(&options);
    EXPECT_EQ(options.Check().find(field), 0u) << options.Check();
  }
}

TEST(SensorModel, UniformWallCornerToCentreMatchesTheConfiguredShadingWithin10Percent) {
  const BandRadianceTable table;
  SensorOptions options;  // every effect on: noise and fixed pattern average out over patches
  options.housing_warming_k_per_min = 1.0;
  options.vignetting_k_per_k = 1.0;
  options.narcissus_k_per_k = 0.5;
  SensorModel model(options, kWidth, kHeight, kFrameRateHz, 3, &table);
  const cv::Mat wall = Uniform(table, static_cast<float>(options.reference_temperature_c));
  // 50 s after the FFC at frame 0 the housing has warmed 50/60 K: 0.83·(1.0 + 0.5) = 1.25 K.
  const double configured = 50.0 / 60.0 * (1.0 + 0.5);
  EXPECT_NEAR(model.ShadingCornerToCentreK(1250), configured, 1e-9);
  double measured = 0.0;
  for (int frame = 1250; frame < 1255; ++frame) measured += CornerMinusCentre(model.Apply(frame, wall), 4);
  measured /= 5.0;
  EXPECT_NEAR(measured, configured, 0.1 * configured);
  // The shading grows with the housing temperature and the next FFC (frame 1500) resets it.
  EXPECT_NEAR(model.ShadingCornerToCentreK(625), configured / 2.0, 1e-9);
  EXPECT_EQ(model.ShadingCornerToCentreK(1500), 0.0);
  SensorOptions off = options;
  off.lens_shading = false;
  SensorModel flat(off, kWidth, kHeight, kFrameRateHz, 3, &table);
  EXPECT_LT(std::abs(CornerMinusCentre(flat.Apply(1250, wall), 4)), 0.1 * configured);
}

TEST(SensorModel, ShadingIsRadialWithWarmCornersAndADarkCentre) {
  const BandRadianceTable table;
  SensorOptions options = AllOff();
  options.lens_shading = true;
  SensorModel model(options, kWidth, kHeight, kFrameRateHz, 3, &table);
  const int frame = 1000;
  const double corner = model.ShadingK(frame, 0, 0);
  EXPECT_NEAR(corner, model.ShadingK(frame, kWidth - 1, kHeight - 1), 1e-6);
  EXPECT_NEAR(corner - model.ShadingK(frame, kWidth / 2, kHeight / 2), model.ShadingCornerToCentreK(frame),
              0.02 * model.ShadingCornerToCentreK(frame));
  EXPECT_GT(model.ShadingK(frame, 40, kHeight / 2), model.ShadingK(frame, kWidth / 2, kHeight / 2));
}

TEST(SensorModel, FramesFrozenDuringAnFfcAreByteIdenticalToTheFrameBefore) {
  const BandRadianceTable table;
  SensorOptions options;
  options.ffc_interval_s = 1.0;  // FFC at frame 25; 0.5 s at 25 Hz freezes 13 frames (25–37)
  SensorModel model(options, kWidth, kHeight, kFrameRateHz, 4, &table);
  ASSERT_EQ(model.FreezeFrames(), 13);
  std::vector<cv::Mat> outputs;
  for (int frame = 0; frame < 40; ++frame) outputs.push_back(model.Apply(frame, MovingScene(table, frame)));
  for (int frame = 25; frame <= 37; ++frame) {
    EXPECT_EQ(model.ShownFrame(frame), 24);
    EXPECT_TRUE(SameBytes(outputs[frame], outputs[24])) << frame;
  }
  EXPECT_EQ(model.ShownFrame(38), 38);
  EXPECT_FALSE(SameBytes(outputs[38], outputs[24]));
  EXPECT_FALSE(SameBytes(outputs[24], outputs[23]));
  SensorOptions no_freeze = options;
  no_freeze.ffc_freeze = false;
  EXPECT_EQ(SensorModel(no_freeze, kWidth, kHeight, kFrameRateHz, 4, &table).FreezeFrames(), 0);
  // The freeze never reaches the next FFC: capped at one frame less than the interval.
  SensorOptions long_freeze = options;
  long_freeze.ffc_freeze_s = 5.0;
  EXPECT_EQ(SensorModel(long_freeze, kWidth, kHeight, kFrameRateHz, 4, &table).FreezeFrames(), 24);
}

TEST(SensorModel, ResumingInsideAFreezeReplaysFromTheFrameItShows) {
  const BandRadianceTable table;
  SensorOptions options;
  options.ffc_interval_s = 1.0;
  SensorModel full_run(options, kWidth, kHeight, kFrameRateHz, 9, &table);
  std::vector<cv::Mat> outputs;
  for (int frame = 0; frame < 42; ++frame) outputs.push_back(full_run.Apply(frame, MovingScene(table, frame)));
  for (int resume_at : {25, 26, 37, 38, 39}) {
    SensorModel resumed(options, kWidth, kHeight, kFrameRateHz, 9, &table);
    const int first = resumed.ReplayFrom(resume_at);
    EXPECT_EQ(first, resume_at <= 37 ? 23 : resume_at - 1);
    for (int frame = first; frame < resume_at; ++frame) resumed.Apply(frame, MovingScene(table, frame));
    for (int frame = resume_at; frame < 42; ++frame) {
      EXPECT_TRUE(SameBytes(resumed.Apply(frame, MovingScene(table, frame)), outputs[frame]))
          << "resumed at " << resume_at << ", frame " << frame;
    }
  }
}

TEST(SensorModel, ResumingAfterPrimingWithThePreviousFrameReproducesTheRun) {
  const BandRadianceTable table;
  SensorOptions quantised;
  quantised.ffc_interval_s = 1.0;  // FFC at frame 25, inside the resumed stretch
  SensorOptions unquantised = quantised;
  unquantised.quantisation = false;  // so that sub-step differences would show
  for (const SensorOptions& options : {quantised, unquantised}) {
    SensorModel full_run(options, kWidth, kHeight, kFrameRateHz, 9, &table);
    std::vector<cv::Mat> outputs;
    for (int frame = 0; frame < 30; ++frame) {
      outputs.push_back(full_run.Apply(frame, MovingScene(table, frame)));
    }
    SensorModel resumed(options, kWidth, kHeight, kFrameRateHz, 9, &table);
    resumed.Apply(19, MovingScene(table, 19));
    for (int frame = 20; frame < 30; ++frame) {
      EXPECT_TRUE(SameBytes(resumed.Apply(frame, MovingScene(table, frame)), outputs[frame])) << frame;
    }
    // Without priming the time constant starts from a steady scene: the moving edge differs.
    SensorModel unprimed(options, kWidth, kHeight, kFrameRateHz, 9, &table);
    EXPECT_FALSE(SameBytes(unprimed.Apply(20, MovingScene(table, 20)), outputs[20]));
  }
}

TEST(SensorModel, RejectsFramesOutOfOrderAndWrongImages) {
  const BandRadianceTable table;
  SensorModel model(SensorOptions(), kWidth, kHeight, kFrameRateHz, 1, &table);
  model.Apply(3, Uniform(table, 22.0f));
  EXPECT_THROW(model.Apply(5, Uniform(table, 22.0f)), std::logic_error);
  EXPECT_THROW(model.Apply(4, cv::Mat(10, 10, CV_32F, cv::Scalar(50.0f))), std::logic_error);
  EXPECT_THROW(model.Apply(4, cv::Mat(kHeight, kWidth, CV_64F, cv::Scalar(50.0))), std::logic_error);
  SensorOptions bad;
  bad.netd_k = -1.0;
  EXPECT_THROW(SensorModel(bad, kWidth, kHeight, kFrameRateHz, 1, &table), std::logic_error);
}

}  // namespace
}  // namespace hoilcd
