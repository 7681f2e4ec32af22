#include "hoilcd/core/features/hoi_features.h"

#include <map>
#include <set>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "option_properties.h"

namespace hoilcd {
namespace {

// Column -> rows set in the mask (a hand-drawable picture of a person's lower edge).
cv::Mat MaskFrom(const std::map<int, std::vector<int>>& rows_of_column) {
  cv::Mat mask = cv::Mat::zeros(12, 12, CV_8U);
  for (const auto& [x, rows] : rows_of_column) {
    for (int y : rows) mask.at<uint8_t>(y, x) = 255;
  }
  return mask;
}

cv::Mat HandMask() {
  return MaskFrom({
      {2, {1, 2, 3, 4, 5}},
      {3, {1, 2, 3, 4, 5, 6}},
      {4, {2, 3, 4, 5, 6, 7, 8, 10}},    // row 10 is below the box: ignored
      {5, {2, 3, 4, 7}},                 // a gap: the lowest pixel counts
      {7, {3, 4}},                       // column 6 is empty: no point
      {8, {1, 2, 3, 4, 5, 6, 7, 8, 9}},  // right of the box: ignored
  });
}

std::vector<std::pair<int, int>> Points(const std::vector<HoiFeature>& features) {
  std::vector<std::pair<int, int>> points;
  for (const HoiFeature& f : features) {
    points.emplace_back(static_cast<int>(f.point.x), static_cast<int>(f.point.y));
  }
  return points;
}

TEST(ExtractHoiFeatures, BottomMostPersonPixelPerColumnOfTheBox) {
  const std::vector<Track> tracks = {{7, cv::Rect2f(2, 1, 6, 8), 0.9f}};  // cols 2-7, rows 1-8
  const std::vector<HoiFeature> features = ExtractHoiFeatures(HandMask(), tracks, {});
  const std::vector<std::pair<int, int>> expected = {{2, 5}, {3, 6}, {4, 8}, {5, 7}, {7, 4}};
  EXPECT_EQ(Points(features), expected);
  for (const HoiFeature& f : features) EXPECT_EQ(f.track_id, 7);
}

TEST(ExtractHoiFeatures, ColumnsAndRowsBelongToABoxByTheirPixelCentres) {
  // x in [1.6, 5.4): centres 2.5, 3.5, 4.5 are in, 1.5 and 5.5 are out; rows [0.7, 6.4): 1..5.
  const std::vector<Track> tracks = {{1, cv::Rect2f(1.6f, 0.7f, 3.8f, 5.7f), 0.9f}};
  const std::vector<std::pair<int, int>> expected = {{2, 5}, {3, 5}, {4, 5}};
  EXPECT_EQ(Points(ExtractHoiFeatures(HandMask(), tracks, {})), expected);
}

TEST(ExtractHoiFeatures, PeopleWithTooFewPointsGiveNone) {
  const std::vector<Track> tracks = {{1, cv::Rect2f(7.6f, 0, 3, 12), 0.9f},  // only column 8
                                     {2, cv::Rect2f(2, 1, 6, 8), 0.9f}};
  const std::vector<HoiFeature> features = ExtractHoiFeatures(HandMask(), tracks, {});
  ASSERT_EQ(features.size(), 5u);
  for (const HoiFeature& f : features) EXPECT_EQ(f.track_id, 2);
  HoiOptions one;
  one.min_points_per_person = 1;
  const std::vector<HoiFeature> all = ExtractHoiFeatures(HandMask(), tracks, one);
  ASSERT_EQ(all.size(), 6u);
  EXPECT_EQ(all[0].track_id, 1);
  EXPECT_EQ(Points(all)[0], std::make_pair(8, 9));
}

TEST(ExtractHoiFeatures, BoxesAreClippedToTheImageAndColumnsCanBeSubsampled) {
  HoiOptions options;
  options.min_points_per_person = 1;
  const std::vector<Track> outside = {{3, cv::Rect2f(-5, -5, 8, 8), 0.9f}};  // cols 0-2, rows 0-2
  EXPECT_EQ(Points(ExtractHoiFeatures(HandMask(), outside, options)), (std::vector<std::pair<int, int>>{{2, 2}}));
  options.column_step_px = 2;
  const std::vector<Track> tracks = {{1, cv::Rect2f(2, 1, 6, 8), 0.9f}};
  EXPECT_EQ(Points(ExtractHoiFeatures(HandMask(), tracks, options)),
            (std::vector<std::pair<int, int>>{{2, 5}, {4, 8}}));
}

TEST(HoiOptions, CheckNamesTheBadField) {
  EXPECT_EQ(HoiOptions{}.Check(), "");
  HoiOptions bad;
  bad.column_step_px = 0;
  EXPECT_NE(bad.Check().find("column_step_px"), std::string::npos);
  EXPECT_THROW(ExtractHoiFeatures(HandMask(), {}, bad), std::logic_error);
}

TEST(HoiOptions, HoldTheirTablesDefaultsAndEveryBoundIsChecked) {
  EXPECT_EQ(HoiOptions().column_step_px, 1);  // every column, as the paper
  ExpectConstructedHoldsTheTableDefaults<HoiOptions>();
  EXPECT_EQ(ExpectEveryBoundCrossedIsNamedByCheck<HoiOptions>(), 2);
}

// Two seated people (torsos touching) drift right by 1 px per frame: the front end keeps two
// ids and puts their HOI points on the bottom edge (row 104) of each torso.
TEST(DlcdFrontEnd, TwoSeatedPeopleGiveTwoIdsWithPointsOnTheirBottomEdges) {
  DlcdFrontEnd front_end({}, {}, {});
  std::set<int> ids;
  for (int frame = 0; frame < 8; ++frame) {
    cv::Mat frame_c(192, 256, CV_32F, cv::Scalar(22));
    for (int torso_x : {80 + frame, 110 + frame}) {
      cv::rectangle(frame_c, cv::Rect(torso_x, 55, 30, 50), cv::Scalar(28.5), cv::FILLED);
      cv::ellipse(frame_c, cv::Point(torso_x + 15, 48), cv::Size(7, 9), 0, 0, 360, cv::Scalar(34), cv::FILLED);
    }
    const std::vector<HoiFeature> features = front_end.Process(cv::Mat(), frame_c);
    ASSERT_EQ(front_end.last_detections().detections.size(), 2u) << "frame " << frame;
    ASSERT_EQ(front_end.last_tracks().size(), 2u) << "frame " << frame;
    std::map<int, int> points_per_id;
    for (const HoiFeature& f : features) {
      ids.insert(f.track_id);
      // The morphological opening rounds the torso's bottom corners off by one row.
      EXPECT_NEAR(f.point.y, 104, 1) << "frame " << frame;
      if (f.point.y == 104) ++points_per_id[f.track_id];
      EXPECT_GE(f.point.x, 79 + frame);
      EXPECT_LE(f.point.x, 140 + frame);
    }
    ASSERT_EQ(points_per_id.size(), 2u);
    for (const auto& [id, count] : points_per_id) EXPECT_GE(count, 25) << "id " << id;
  }
  EXPECT_EQ(ids, (std::set<int>{1, 2}));
}

}  // namespace
}  // namespace hoilcd
