#include "hoilcd/bench/realism/realism.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "hoilcd/bench/realism/frame_size_groups.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

TEST(Realism, WassersteinOfKnownDistributions) {
  EXPECT_DOUBLE_EQ(Wasserstein1({1, 2, 3}, {1, 2, 3}), 0.0);
  EXPECT_DOUBLE_EQ(Wasserstein1({0, 1}, {0.5, 1.5}), 0.5);  // a shift moves every unit of mass by it
  EXPECT_DOUBLE_EQ(Wasserstein1({0}, {0, 1}), 0.5);         // half the mass moves by 1
  EXPECT_DOUBLE_EQ(Wasserstein1({0, 0, 0, 4}, {1, 1, 1, 1}), 3.0 / 4 * 1 + 1.0 / 4 * 3);
  EXPECT_DOUBLE_EQ(Wasserstein1({3, 1, 2}, {2, 3, 1}), 0.0);  // order does not matter
  EXPECT_TRUE(std::isnan(Wasserstein1({}, {1})));
  // Two normal samples a distance d apart: W1 -> d.
  std::mt19937 rng(1);
  std::normal_distribution<double> normal;
  std::vector<double> a, b;
  for (int i = 0; i < 20000; ++i) {
    a.push_back(normal(rng));
    b.push_back(normal(rng) + 2.0);
  }
  EXPECT_NEAR(Wasserstein1(a, b), 2.0, 0.05);
  // Uniform(0, 1) against a point at 0.5: the mean distance, 1/4.
  std::vector<double> uniform, point(100, 0.5);
  for (int i = 0; i < 1000; ++i) uniform.push_back((i + 0.5) / 1000);
  EXPECT_NEAR(Wasserstein1(uniform, point), 0.25, 1e-3);
}

FrameStatistics Frame(double corners, bool blank, double spread_k) {
  FrameStatistics s;
  s.shi_tomasi_corners = corners;
  s.radiometric = !std::isnan(spread_k);
  s.spread_k = spread_k;
  s.blank = blank;
  return s;
}

TEST(Realism, ComparisonGivesMediansRatiosAndNotBlankViewsApart) {
  FrameSet synthetic, real;
  synthetic.frames = {"0", "1", "2", "3"};
  synthetic.statistics = {Frame(10, true, 0.5), Frame(10, true, 0.6), Frame(100, false, 5), Frame(120, false, 6)};
  real.frames = {"a.png", "b.png", "c.jpg"};
  real.statistics = {Frame(200, false, 8), Frame(240, false, 10), Frame(400, false, NAN)};
  synthetic.temporal_noise_k = {0.05, 0.07};
  const RealismComparison c = CompareFrameSets(synthetic, real);
  ASSERT_EQ(c.rows.size(), FrameStatisticList().size() + 1);
  const StatisticRow& corners = c.rows[0];
  EXPECT_EQ(corners.key, "shi_tomasi_corners");
  EXPECT_DOUBLE_EQ(corners.all.synthetic.median, 55);
  EXPECT_DOUBLE_EQ(corners.not_blank.synthetic.median, 110);
  EXPECT_DOUBLE_EQ(corners.all.real.median, 240);
  EXPECT_DOUBLE_EQ(corners.not_blank.median_ratio, 110.0 / 240);
  EXPECT_EQ(corners.all.real.count, 3);
  // The 8-bit frame has no spread: two real values.
  for (const StatisticRow& row : c.rows) {
    if (row.key != "temperature_spread_k") continue;
    EXPECT_EQ(row.all.real.count, 2);
    EXPECT_DOUBLE_EQ(row.all.real.median, 9);
    EXPECT_DOUBLE_EQ(row.not_blank.synthetic.median, 5.5);
  }
  EXPECT_EQ(c.rows.back().key, "temporal_noise_k");
  EXPECT_NEAR(c.rows.back().all.synthetic.median, 0.06, 1e-12);
  EXPECT_EQ(c.rows.back().all.real.count, 0);
  EXPECT_TRUE(std::isnan(c.rows.back().all.wasserstein1));
  EXPECT_EQ(c.synthetic.Blank(), 2);
  const nlohmann::json j = c.ToJson();
  EXPECT_EQ(j["synthetic"]["blank_share"], 0.5);
  EXPECT_EQ(j["real"]["radiometric"], 2);
  EXPECT_EQ(j["statistics"][0]["views_not_blank"]["synthetic"]["median"], 110);
  const std::string md = c.ToMarkdown();
  EXPECT_NE(md.find("## Views that are not blank"), std::string::npos);
  EXPECT_NE(md.find("| Shi-Tomasi corners | 240 (220–320, n 3) | 110 (105–115, n 2) | 0.46 |"), std::string::npos)
      << md;
  EXPECT_NE(md.find("1 8-bit: no temperature statistics for those"), std::string::npos);
}

FrameStatistics SizedFrame(int width, int height, bool blank, double slope, double noise_k, double lag1) {
  FrameStatistics s;
  s.width_px = width;
  s.height_px = height;
  s.radiometric = true;
  s.blank = blank;
  s.spectrum_slope = slope;
  s.flat_noise_k = noise_k;
  s.flat_noise_lag1 = lag1;
  return s;
}

TEST(Realism, FrameSizeGroupsGiveMediansOverViewsNotBlankPerSize) {
  const std::vector<FrameStatistics> frames = {
      SizedFrame(320, 240, false, -3.5, 0.02, 0.7), SizedFrame(160, 120, false, -2.9, 0.1, 0.6),
      SizedFrame(320, 240, false, -3.3, 0.03, 0.8), SizedFrame(320, 240, true, -1.0, 0.5, 0.0),
      SizedFrame(640, 512, true, -3.0, 0.1, 0.1)};
  const std::vector<FrameSizeGroup> groups = GroupByFrameSize(frames);
  ASSERT_EQ(groups.size(), 3u);
  // The most frames first, then by width.
  EXPECT_EQ(groups[0].width_px, 320);
  EXPECT_EQ(groups[0].height_px, 240);
  EXPECT_EQ(groups[0].views, 3);
  EXPECT_EQ(groups[0].not_blank, 2);
  EXPECT_DOUBLE_EQ(groups[0].spectrum_slope, -3.4);  // the blank view left out
  EXPECT_DOUBLE_EQ(groups[0].flat_noise_k, 0.025);
  EXPECT_DOUBLE_EQ(groups[0].flat_noise_lag1, 0.75);
  EXPECT_EQ(groups[1].width_px, 160);
  EXPECT_EQ(groups[2].width_px, 640);
  EXPECT_EQ(groups[2].not_blank, 0);
  EXPECT_TRUE(std::isnan(groups[2].spectrum_slope));
  const nlohmann::json j = FrameSizeGroupsJson(groups);
  EXPECT_EQ(j[0]["views_not_blank"], 2);
  EXPECT_TRUE(j[2]["spectrum_slope_median"].is_null());

  FrameSet synthetic, real;
  synthetic.frames = {"0"};
  synthetic.statistics = {SizedFrame(256, 192, false, -2.93, 0.066, -0.04)};
  real.frames = {"a", "b", "c", "d", "e"};
  real.statistics = frames;
  const RealismComparison c = CompareFrameSets(synthetic, real);
  const std::string md = c.ToMarkdown();
  EXPECT_NE(md.find("## By frame size"), std::string::npos) << md;
  EXPECT_NE(md.find("the only camera identity a .npy or PNG carries"), std::string::npos);
  EXPECT_NE(md.find("| real | 320×240 | 3 | 2 | -3.40 | 0.025 | 0.75 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| real | 640×512 | 1 | 0 | – | – | – |"), std::string::npos) << md;
  EXPECT_NE(md.find("| synthetic | 256×192 | 1 | 1 | -2.93 | 0.066 | -0.04 |"), std::string::npos) << md;
  const nlohmann::json report = c.ToJson();
  EXPECT_EQ(report["by_frame_size"]["real"].size(), 3u);
  EXPECT_EQ(report["by_frame_size"]["synthetic"][0]["width_px"], 256);
  EXPECT_EQ(report["real"]["per_frame"][1]["width_px"], 160);
  EXPECT_EQ(report["real"]["per_frame"][1]["flat_noise_lag1"], 0.6);
}

TEST(Realism, StaticPairsAreFramesWhoseCameraBarelyMoved) {
  std::vector<PoseRecord> poses(4);
  poses[1].cam_x_m = 0.001;  // 1 mm: static
  poses[2].cam_x_m = 0.001;
  poses[2].cam_yaw_rad = 0.001;  // 0.057 deg: moving
  poses[3] = poses[2];
  EXPECT_TRUE(IsStaticPair(poses, 0));
  EXPECT_FALSE(IsStaticPair(poses, 1));
  EXPECT_TRUE(IsStaticPair(poses, 2));
  EXPECT_FALSE(IsStaticPair(poses, 3));  // no next frame
  EXPECT_EQ(StridedFrames(7, 3), (std::vector<int>{0, 3, 6}));
}

TEST(Realism, AStaticRealSequenceGivesItsTemporalNoise) {
  const test::TestDir dir;
  std::mt19937 rng(3);
  std::normal_distribution<float> noise(22.0f, 0.05f);
  for (int i = 0; i < 4; ++i) {
    cv::Mat t(kStatisticsHeightPx, kStatisticsWidthPx, CV_32F);
    for (int y = 0; y < t.rows; ++y)
      for (int x = 0; x < t.cols; ++x) t.at<float>(y, x) = noise(rng) + 0.01f * static_cast<float>(x);
    ASSERT_TRUE(cv::imwrite(dir / ("frame_" + std::to_string(i) + ".tiff"), t));
  }
  ASSERT_TRUE(cv::imwrite(dir / "frame_9.png", cv::Mat(120, 160, CV_8U, cv::Scalar(7))));  // 8-bit: no pair
  FrameSet still = MeasureRealFrames(dir.str(), {}, true, 1);
  ASSERT_EQ(still.frames.size(), 5u);
  EXPECT_EQ(still.Radiometric(), 4);
  ASSERT_EQ(still.temporal_noise_k.size(), 3u);
  for (double k : still.temporal_noise_k) EXPECT_NEAR(k, 0.05, 0.003);
  EXPECT_TRUE(MeasureRealFrames(dir.str(), {}, false, 2).temporal_noise_k.empty());
  // The same statistics at any thread count.
  const FrameSet two = MeasureRealFrames(dir.str(), {}, true, 2);
  EXPECT_EQ(two.temporal_noise_k, still.temporal_noise_k);
  EXPECT_EQ(two.statistics[0].spectrum_slope, still.statistics[0].spectrum_slope);
}

}  // namespace
}  // namespace hoilcd
