#include "hoilcd/bench/report/figures.h"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "hoilcd/bench/report/chart.h"
#include "option_properties.h"

namespace hoilcd {
namespace {

const cv::Scalar kMagenta(255, 0, 255);  // not in the palette, not a grey

MatchTile MakeTile(cv::Mat image, std::string caption, std::vector<cv::Point2f> points = {}) {
  MatchTile tile;
  tile.image = std::move(image);
  tile.caption = std::move(caption);
  tile.points = std::move(points);
  return tile;
}

// Pixels of exactly `colour` inside / outside `area`.
std::pair<int, int> CountColour(const cv::Mat& image, const cv::Scalar& colour, cv::Rect area) {
  cv::Mat mask;
  cv::inRange(image, colour, colour, mask);
  const int inside = cv::countNonZero(mask(area & cv::Rect(0, 0, image.cols, image.rows)));
  return {inside, cv::countNonZero(mask) - inside};
}

TEST(MosaicOptions, CheckRejectsABadScale) {
  EXPECT_EQ(MosaicOptions{}.Check(), "");
  MosaicOptions m;
  m.scale = 0;
  EXPECT_NE(m.Check().find("scale"), std::string::npos);
  EXPECT_THROW(MatchMosaic({}, m), std::logic_error);
}

TEST(MosaicOptions, HoldTheirTablesDefaultsAndEveryBoundIsChecked) {
  ExpectConstructedHoldsTheTableDefaults<MosaicOptions>();
  EXPECT_EQ(ExpectEveryBoundCrossedIsNamedByCheck<MosaicOptions>(), 6);
}

TEST(TrajectoryPlot, MetresHaveEqualLengthOnBothAxes) {
  // Grey dots spread 8 m in x and 1 m in y; magenta dots on the corners of a 1 m square.
  std::vector<TrajectoryPoint> points;
  for (int i = 0; i <= 80; ++i) points.push_back({-3.0 + 0.1 * i, 0.5 * std::sin(i * 0.3), {128, 128, 128}});
  for (const cv::Point2d corner : {cv::Point2d(0, 0), cv::Point2d(1, 0), cv::Point2d(0, 1), cv::Point2d(1, 1)}) {
    points.push_back({corner.x, corner.y + 2.0, kMagenta});
  }
  FootprintRecord box;
  box.name = "table";
  box.centre_m = {3.5, 1.5};
  box.half_size_m = {0.5, 0.5};
  const std::vector<FootprintRecord> obstacles = {box};
  PlotOptions o;
  o.width_px = 500;
  o.height_px = 500;
  cv::Rect area;
  const cv::Mat image = TrajectoryPlot(points, {}, obstacles, {}, o, &area);
  EXPECT_EQ(image.size(), cv::Size(500, 500));
  EXPECT_EQ(CountColour(image, kMagenta, area).second, 0);
  cv::Mat magenta;
  cv::inRange(image, kMagenta, kMagenta, magenta);
  cv::Mat labels, stats, centroids;
  ASSERT_EQ(cv::connectedComponentsWithStats(magenta, labels, stats, centroids), 5);  // + background
  std::vector<cv::Point2d> centres;
  for (int i = 1; i < 5; ++i) centres.emplace_back(centroids.at<double>(i, 0), centroids.at<double>(i, 1));
  double min_x = 1e9, max_x = -1e9, min_y = 1e9, max_y = -1e9;
  for (const cv::Point2d& c : centres) {
    min_x = std::min(min_x, c.x);
    max_x = std::max(max_x, c.x);
    min_y = std::min(min_y, c.y);
    max_y = std::max(max_y, c.y);
  }
  EXPECT_GT(max_x - min_x, 20.0);
  EXPECT_NEAR(max_x - min_x, max_y - min_y, 1.0);
  // The 1 m x 1 m obstacle is a square too.
  cv::Mat fill;
  cv::inRange(image(area), cv::Scalar::all(218), cv::Scalar::all(218), fill);
  const int count = cv::connectedComponentsWithStats(fill, labels, stats, centroids);
  int largest = 0;  // anti-aliased dot edges can have the same grey: take the largest patch
  for (int i = 1; i < count; ++i) {
    if (largest == 0 || stats.at<int>(i, cv::CC_STAT_AREA) > stats.at<int>(largest, cv::CC_STAT_AREA)) {
      largest = i;
    }
  }
  ASSERT_GT(largest, 0);
  EXPECT_NEAR(stats.at<int>(largest, cv::CC_STAT_WIDTH), stats.at<int>(largest, cv::CC_STAT_HEIGHT), 1);
  EXPECT_NEAR(stats.at<int>(largest, cv::CC_STAT_WIDTH), max_x - min_x, 3.0);
}

TEST(MatchMosaic, SizeIsTheSumOfTileSizesTimesScalePlusGaps) {
  const cv::Mat gray(192, 256, CV_8UC1, cv::Scalar(100));
  const cv::Mat bgr(192, 256, CV_8UC3, cv::Scalar(10, 20, 30));
  cv::Mat celsius(48, 64, CV_32FC1);
  cv::randu(celsius, 20.0f, 36.0f);
  MatchTile query = MakeTile(gray, "query 12", {{10.0f, 20.0f}, {100.5f, 150.0f}});
  MatchTile features = MakeTile(bgr, "features");
  MatchTile small = MakeTile(celsius, "");
  MatchTile missing = MakeTile(cv::Mat(), "no true match");
  MosaicOptions o;
  o.scale = 2;
  o.gap_px = 0;
  cv::Mat mosaic = MatchMosaic({{query, features, small}, {query, missing}}, o);
  EXPECT_EQ(mosaic.type(), CV_8UC3);
  EXPECT_EQ(mosaic.cols, (256 + 256 + 64) * 2);
  EXPECT_EQ(mosaic.rows, (192 + 192) * 2);
  o.scale = 3;
  o.gap_px = 5;
  mosaic = MatchMosaic({{query, features, small}, {query, missing}}, o);
  EXPECT_EQ(mosaic.cols, (256 + 256 + 64) * 3 + 2 * 5);
  EXPECT_EQ(mosaic.rows, (192 + 192) * 3 + 5);
}

TEST(MatchMosaic, UpscalesWithNearestNeighbour) {
  cv::Mat image(8, 8, CV_8UC3);
  cv::randu(image, 0, 255);
  const cv::Mat mosaic = MatchMosaic({{MakeTile(image, "")}}, MosaicOptions{});
  ASSERT_EQ(mosaic.size(), cv::Size(16, 16));
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 8; ++x) {
      for (const cv::Point d : {cv::Point(0, 0), cv::Point(1, 0), cv::Point(0, 1), cv::Point(1, 1)}) {
        EXPECT_EQ(mosaic.at<cv::Vec3b>(2 * y + d.y, 2 * x + d.x), image.at<cv::Vec3b>(y, x));
      }
    }
  }
}

TEST(MatchMosaic, ACaptionWiderThanItsTileIsDrawnSmallerToFit) {
  // Black 256 px tiles at scale 1, as in the report's match pictures: a top-1 caption with a
  // tie note is wider than its tile at the default size and was cut off at the tile's edge.
  const cv::Mat black(192, 256, CV_8UC3, cv::Scalar::all(0));
  const std::string caption = "top-1 1234 wrong s=47 (12 tied)";
  MosaicOptions o;
  o.scale = 1;
  o.gap_px = 0;
  ASSERT_GT(chart::TextSize(caption, o.font_scale).width + 10, 256);
  const cv::Mat mosaic = MatchMosaic({{MakeTile(black, caption), MakeTile(black, "")}}, o);
  cv::Mat lit;
  cv::inRange(mosaic, cv::Scalar::all(1), cv::Scalar::all(255), lit);
  EXPECT_GT(cv::countNonZero(lit(cv::Rect(0, 0, 256, 192))), 100);          // the caption is drawn
  EXPECT_EQ(cv::countNonZero(lit(cv::Rect(256 - 4, 0, 4 + 256, 192))), 0);  // inside its 5 px margin
}

}  // namespace
}  // namespace hoilcd
