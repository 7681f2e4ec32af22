#include "hoilcd/core/features/person_detection.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "hoilcd/core/util/random.h"
#include "option_properties.h"

namespace hoilcd {
namespace {

constexpr float kRoomC = 22.0f, kSkinC = 34.0f, kClothingC = 28.5f;

// A seated person seen from the front: a head on a torso.
void DrawPerson(cv::Mat& frame_c, int torso_x, int torso_top, int torso_width, int torso_height) {
  cv::rectangle(frame_c, cv::Rect(torso_x, torso_top, torso_width, torso_height), cv::Scalar(kClothingC), cv::FILLED);
  cv::ellipse(frame_c, cv::Point(torso_x + torso_width / 2, torso_top - 7), cv::Size(7, 9), 0, 0, 360,
              cv::Scalar(kSkinC), cv::FILLED);
}

void AddNoise(cv::Mat& frame_c, int frame) {
  for (int y = 0; y < frame_c.rows; ++y) {
    for (int x = 0; x < frame_c.cols; ++x) {
      Rng rng = KeyedRng(11, "test.person_detection.noise", frame, y * frame_c.cols + x);
      frame_c.at<float>(y, x) += static_cast<float>(rng.Normal(0, 0.15));
    }
  }
}

// Two people whose torsos touch at column 110, a small and a larger hot cup, a laptop and a
// radiator, on a 22 degC room.
cv::Mat SceneC() {
  cv::Mat frame_c(192, 256, CV_32F, cv::Scalar(kRoomC));
  DrawPerson(frame_c, 80, 55, 30, 50);
  DrawPerson(frame_c, 110, 58, 30, 47);
  cv::circle(frame_c, cv::Point(200, 100), 4, cv::Scalar(45), cv::FILLED);
  cv::circle(frame_c, cv::Point(225, 100), 7, cv::Scalar(48), cv::FILLED);
  cv::rectangle(frame_c, cv::Rect(160, 140, 40, 10), cv::Scalar(32), cv::FILLED);
  cv::rectangle(frame_c, cv::Rect(10, 160, 70, 22), cv::Scalar(40), cv::FILLED);
  AddNoise(frame_c, 0);
  return frame_c;
}

cv::Mat ToDisplayU8(const cv::Mat& frame_c) {
  cv::Mat u8;
  frame_c.convertTo(u8, CV_8U, 255.0 / 10.0, -20.0 * 255.0 / 10.0);  // saturating 20-30 degC
  return u8;
}

void ExpectTheTwoTouchingPeople(const PersonDetections& result) {
  ASSERT_EQ(result.detections.size(), 2u);
  const cv::Rect2f left = result.detections[0].box, right = result.detections[1].box;
  // The split falls where the torsos meet (column 110), within a pixel or two.
  EXPECT_NEAR(left.x, 80, 1);
  EXPECT_NEAR(left.x + left.width, 110, 2);
  EXPECT_NEAR(right.x, 110, 2);
  EXPECT_NEAR(right.x + right.width, 140, 1);
  EXPECT_NEAR(left.y, 55 - 16, 2);  // top of the head
  EXPECT_NEAR(left.y + left.height, 105, 1);
  for (const Detection& d : result.detections) {
    EXPECT_GE(d.score, 0.6f) << "a clear person must be able to start a track";
    EXPECT_LE(d.score, 1.0f);
  }
  ASSERT_EQ(result.mask.type(), CV_8UC1);
  EXPECT_EQ(result.mask.at<uint8_t>(80, 95), 255);
  EXPECT_EQ(result.mask.at<uint8_t>(80, 125), 255);
  EXPECT_EQ(result.mask.at<uint8_t>(100, 200), 0) << "cup pixels are not person pixels";
  EXPECT_EQ(result.mask.at<uint8_t>(100, 225), 0) << "cup pixels are not person pixels";
  EXPECT_EQ(result.mask.at<uint8_t>(145, 180), 0) << "laptop pixels are not person pixels";
  EXPECT_EQ(result.mask.at<uint8_t>(170, 40), 0) << "radiator pixels are not person pixels";
}

TEST(DetectPersons, SplitsTwoTouchingPeopleAndIgnoresCupsLaptopAndRadiator) {
  ExpectTheTwoTouchingPeople(DetectPersons(cv::Mat(), SceneC(), PersonDetectorOptions{}));
}

TEST(DetectPersons, WorksOnTheEightBitImageAloneToo) {
  ExpectTheTwoTouchingPeople(DetectPersons(ToDisplayU8(SceneC()), cv::Mat(), {}));
}

TEST(DetectPersons, TheEightBitThresholdFollowsTheDisplayWindow) {
  // The same scene shown in a 15-45 degC window: told that window, the detector thresholds at
  // threshold_c and finds both people; told the default 20-30, its level would mean 34.5 degC.
  cv::Mat u8;
  SceneC().convertTo(u8, CV_8U, 255.0 / 30.0, -15.0 * 255.0 / 30.0);
  PersonDetectorOptions wide;
  wide.u8_min_c = 15;
  wide.u8_max_c = 45;
  ExpectTheTwoTouchingPeople(DetectPersons(u8, cv::Mat(), wide));
  EXPECT_TRUE(DetectPersons(u8, cv::Mat(), {}).detections.empty());
}

TEST(DetectPersons, AThresholdAboveTheDisplayWindowFindsNobody) {
  PersonDetectorOptions above;
  above.threshold_c = 31;  // above 30 degC: no 8-bit level of the 20-30 window reaches it
  const PersonDetections result = DetectPersons(ToDisplayU8(SceneC()), cv::Mat(), above);
  EXPECT_TRUE(result.detections.empty());
  EXPECT_EQ(cv::countNonZero(result.mask), 0);
}

TEST(DetectPersons, RadiometricFrameTakesPrecedenceOverTheEightBitOne) {
  const cv::Mat blank_u8(192, 256, CV_8U, cv::Scalar(0));
  ExpectTheTwoTouchingPeople(DetectPersons(blank_u8, SceneC(), {}));
}

TEST(DetectPersons, ASinglePersonIsNotSplit) {
  cv::Mat frame_c(192, 256, CV_32F, cv::Scalar(kRoomC));
  DrawPerson(frame_c, 100, 60, 34, 50);
  AddNoise(frame_c, 1);
  const PersonDetections result = DetectPersons(cv::Mat(), frame_c, {});
  ASSERT_EQ(result.detections.size(), 1u);
  EXPECT_NEAR(result.detections[0].box.width, 34, 1);
}

TEST(DetectPersons, AnUprightLaptopScreenOfPersonLikeProportionsIsRejected) {
  cv::Mat frame_c(192, 256, CV_32F, cv::Scalar(kRoomC));
  cv::rectangle(frame_c, cv::Rect(100, 80, 30, 24), cv::Scalar(32), cv::FILLED);
  AddNoise(frame_c, 2);
  EXPECT_TRUE(DetectPersons(cv::Mat(), frame_c, {}).detections.empty());
  EXPECT_TRUE(DetectPersons(ToDisplayU8(frame_c), cv::Mat(), {}).detections.empty());
  // A cooler rectangle of the same shape is still rejected for being a rectangle.
  cv::rectangle(frame_c, cv::Rect(100, 80, 30, 24), cv::Scalar(28), cv::FILLED);
  EXPECT_TRUE(DetectPersons(cv::Mat(), frame_c, {}).detections.empty());
}

TEST(DetectPersons, APersonHoldingAHotCupIsStillAPerson) {
  cv::Mat frame_c(192, 256, CV_32F, cv::Scalar(kRoomC));
  DrawPerson(frame_c, 100, 60, 34, 50);
  cv::circle(frame_c, cv::Point(100, 95), 5, cv::Scalar(50), cv::FILLED);
  AddNoise(frame_c, 3);
  EXPECT_EQ(DetectPersons(cv::Mat(), frame_c, {}).detections.size(), 1u);
}

TEST(DetectPersons, ColderThanClothingIsNotAPerson) {
  cv::Mat frame_c(192, 256, CV_32F, cv::Scalar(kRoomC));
  cv::rectangle(frame_c, cv::Rect(100, 60, 30, 50), cv::Scalar(25.5), cv::FILLED);
  EXPECT_TRUE(DetectPersons(cv::Mat(), frame_c, {}).detections.empty());
}

TEST(DetectPersons, SmallerPeopleScoreLower) {
  cv::Mat frame_c(192, 256, CV_32F, cv::Scalar(kRoomC));
  DrawPerson(frame_c, 30, 60, 34, 60);
  DrawPerson(frame_c, 180, 80, 12, 20);
  const PersonDetections result = DetectPersons(cv::Mat(), frame_c, {});
  ASSERT_EQ(result.detections.size(), 2u);
  EXPECT_GT(result.detections[0].score, result.detections[1].score);
  EXPECT_GT(result.detections[1].score, 0.0f);
}

TEST(DetectPersons, OverlappingPeopleAreSplitBetweenTheirHeads) {
  // A far person (torso 70-110) half hidden by a near one (torso 95-140): the column profile has
  // no valley, the two faces tell them apart.
  cv::Mat frame_c(192, 256, CV_32F, cv::Scalar(kRoomC));
  DrawPerson(frame_c, 70, 50, 40, 45);
  DrawPerson(frame_c, 95, 62, 45, 48);
  AddNoise(frame_c, 4);
  const PersonDetections result = DetectPersons(cv::Mat(), frame_c, {});
  ASSERT_EQ(result.detections.size(), 2u);
  const cv::Rect2f left = result.detections[0].box, right = result.detections[1].box;
  // Heads span columns 83-97 and 110-124: the cut falls in the gap between them.
  EXPECT_NEAR(left.x, 70, 1);
  EXPECT_NEAR(right.x, 104, 2);
  EXPECT_NEAR(right.x + right.width, 140, 1);
  EXPECT_NEAR(left.y, 50 - 16, 2);
  EXPECT_NEAR(right.y, 62 - 16, 2);
  // Without temperatures above 30 degC there are no heads and the blob stays whole.
  EXPECT_EQ(DetectPersons(ToDisplayU8(frame_c), cv::Mat(), {}).detections.size(), 1u);
}

TEST(DetectPersons, LegsBelowATableJoinThePersonAbove) {
  cv::Mat frame_c(192, 256, CV_32F, cv::Scalar(kRoomC));
  DrawPerson(frame_c, 100, 60, 34, 40);  // down to the table edge at row 100
  // Legs below the table; not a rectangle, which would be rejected as an object on its own.
  cv::ellipse(frame_c, cv::Point(117, 145), cv::Size(9, 15), 0, 0, 360, cv::Scalar(kClothingC), cv::FILLED);
  AddNoise(frame_c, 5);
  const PersonDetections result = DetectPersons(cv::Mat(), frame_c, {});
  ASSERT_EQ(result.detections.size(), 1u);
  EXPECT_NEAR(result.detections[0].box.y, 60 - 16, 2);
  EXPECT_NEAR(result.detections[0].box.y + result.detections[0].box.height, 160, 1);
  EXPECT_EQ(result.mask.at<uint8_t>(145, 115), 255);
}

TEST(DetectPersons, APersonWithOneHeadIsNotSplitAtAGapBesideTheArm) {
  // A cold slit between torso and arm makes a deep column valley; one face means one person.
  cv::Mat frame_c(192, 256, CV_32F, cv::Scalar(kRoomC));
  DrawPerson(frame_c, 100, 60, 40, 50);
  cv::rectangle(frame_c, cv::Rect(129, 75, 3, 35), cv::Scalar(kRoomC), cv::FILLED);
  AddNoise(frame_c, 6);
  const PersonDetections result = DetectPersons(cv::Mat(), frame_c, {});
  ASSERT_EQ(result.detections.size(), 1u);
  EXPECT_NEAR(result.detections[0].box.width, 40, 1);
}

TEST(DetectPersons, RejectsMismatchedInputs) {
  EXPECT_THROW(DetectPersons(cv::Mat(), cv::Mat(), {}), std::logic_error);
  EXPECT_THROW(DetectPersons(cv::Mat(10, 10, CV_32F), cv::Mat(), {}), std::logic_error);
  EXPECT_THROW(DetectPersons(cv::Mat(10, 10, CV_8U), cv::Mat(12, 10, CV_32F), {}), std::logic_error);
}

TEST(FindSplitColumns, SplitsInTheMiddleOfTheValleyBetweenTwoHeads) {
  // Torso 50 px high everywhere, heads 16 px higher at columns 10-19 and 40-49.
  std::vector<double> counts(60, 50.0);
  for (int c = 10; c < 20; ++c) counts[c] = 66;
  for (int c = 40; c < 50; ++c) counts[c] = 66;
  const std::vector<int> splits = FindSplitColumns(counts, {});
  ASSERT_EQ(splits.size(), 1u);
  EXPECT_NEAR(splits[0], 30, 1);
}

TEST(FindSplitColumns, OneHeadOrAShallowDipGivesNoSplit) {
  std::vector<double> one_head(40, 50.0);
  for (int c = 15; c < 25; ++c) one_head[c] = 66;
  EXPECT_TRUE(FindSplitColumns(one_head, {}).empty());
  std::vector<double> shallow(60, 62.0);
  for (int c = 10; c < 20; ++c) shallow[c] = 66;
  for (int c = 40; c < 50; ++c) shallow[c] = 66;
  EXPECT_TRUE(FindSplitColumns(shallow, {}).empty());
}

TEST(FindSplitColumns, ThreeNeighboursGiveTwoSplits) {
  std::vector<double> counts(90, 45.0);
  for (int base : {10, 40, 70}) {
    for (int c = base; c < base + 10; ++c) counts[c] = 64;
  }
  const std::vector<int> splits = FindSplitColumns(counts, {});
  ASSERT_EQ(splits.size(), 2u);
  EXPECT_NEAR(splits[0], 30, 1);
  EXPECT_NEAR(splits[1], 60, 1);
}

TEST(PersonDetectorOptions, CheckNamesTheBadField) {
  EXPECT_EQ(PersonDetectorOptions{}.Check(), "");
  PersonDetectorOptions bad;
  bad.u8_max_c = bad.u8_min_c;
  EXPECT_NE(bad.Check().find("u8_max_c"), std::string::npos);
  bad = {};
  bad.min_aspect_hw = 6;
  EXPECT_NE(bad.Check().find("min_aspect_hw"), std::string::npos);
  bad = {};
  bad.split_valley_ratio = 1.5;
  EXPECT_NE(bad.Check().find("split_valley_ratio"), std::string::npos);
  bad = {};
  bad.merge_min_overlap = 0;
  EXPECT_NE(bad.Check().find("merge_min_overlap"), std::string::npos);
  bad = {};
  bad.top_skin_zone_ratio = 0;
  EXPECT_NE(bad.Check().find("top_skin_zone_ratio"), std::string::npos);
  bad = {};
  bad.min_top_skin_px = -1;
  EXPECT_NE(bad.Check().find("min_top_skin_px"), std::string::npos);
  bad = {};
  bad.clothing_max_c = 26;
  EXPECT_NE(bad.Check().find("clothing_max_c"), std::string::npos);
  for (double fraction : {-0.1, 1.5}) {
    PersonDetectorOptions wrong;
    wrong.min_clothing_fraction = fraction;
    EXPECT_NE(wrong.Check().find("min_clothing_fraction"), std::string::npos) << fraction;
  }
  EXPECT_THROW(DetectPersons(cv::Mat(), SceneC(), bad), std::logic_error);
  bad = {};
  bad.threshold_c = 40;
  EXPECT_EQ(bad.Check(), "max_median_c: must exceed threshold_c");
}

TEST(PersonDetectorOptions, HoldTheirTablesDefaultsAndEveryBoundIsChecked) {
  ExpectConstructedHoldsTheTableDefaults<PersonDetectorOptions>();
  EXPECT_EQ(ExpectEveryBoundCrossedIsNamedByCheck<PersonDetectorOptions>(), 40);
}

}  // namespace
}  // namespace hoilcd

namespace hoilcd {
namespace {

TEST(PersonDetection, AWarmMonitorWithAStraightTopIsNotAPerson) {
  // A 30 °C monitor back (a rectangle on a stand, a hot cup merged at its foot) on a 22 °C room.
  cv::Mat t(192, 256, CV_32F, cv::Scalar(22.0f));
  cv::rectangle(t, cv::Rect(100, 60, 40, 28), cv::Scalar(29.6f), cv::FILLED);
  cv::rectangle(t, cv::Rect(116, 88, 8, 14), cv::Scalar(29.0f), cv::FILLED);
  cv::circle(t, cv::Point(132, 98), 4, cv::Scalar(45.0f), cv::FILLED);
  EXPECT_TRUE(DetectPersons(cv::Mat(), t, PersonDetectorOptions{}).detections.empty());
  PersonDetectorOptions without_rule;
  without_rule.max_flat_top_fraction = 1.0;  // neither skin nor clothing: rejected too
  EXPECT_TRUE(DetectPersons(cv::Mat(), t, without_rule).detections.empty());
  without_rule.min_top_skin_px = 0;  // the other rules alone take it for a person
  EXPECT_EQ(DetectPersons(cv::Mat(), t, without_rule).detections.size(), 1u);
  // The same blob with a round head on top is a person.
  cv::circle(t, cv::Point(120, 52), 10, cv::Scalar(33.0f), cv::FILLED);
  EXPECT_EQ(DetectPersons(cv::Mat(), t, PersonDetectorOptions{}).detections.size(), 1u);
}

// A laptop on a table seen from the side, as in rendered empty-room frames: the opened lid a
// slanted bar (30 degC, reads 29.6 through emissivity 0.9), the base a strip under it (32 degC,
// reads 31), a hot cup beside it, blurred by the optics.
cv::Mat SideViewLaptopC() {
  cv::Mat t(192, 256, CV_32F, cv::Scalar(kRoomC));
  const std::vector<cv::Point> lid = {{100, 60}, {108, 60}, {117, 85}, {109, 85}};
  cv::fillConvexPoly(t, lid, cv::Scalar(29.6));
  cv::rectangle(t, cv::Rect(109, 84, 26, 3), cv::Scalar(31.0), cv::FILLED);
  cv::circle(t, cv::Point(128, 81), 5, cv::Scalar(45.0), cv::FILLED);
  cv::GaussianBlur(t, t, cv::Size(5, 5), 0.7);
  AddNoise(t, 7);
  return t;
}

TEST(PersonDetection, AWarmLaptopSeenFromTheSideIsNotAPerson) {
  const cv::Mat t = SideViewLaptopC();
  EXPECT_TRUE(DetectPersons(cv::Mat(), t, PersonDetectorOptions{}).detections.empty());
  PersonDetectorOptions without_rule;
  without_rule.min_top_skin_px = 0;  // the shape and temperature rules alone take it for a person
  EXPECT_EQ(DetectPersons(cv::Mat(), t, without_rule).detections.size(), 1u);
}

TEST(PersonDetection, WithoutVisibleSkinAPersonIsMostlyClothing) {
  // Seen from behind and close, the shoulders hide the head: a rounded torso, clothing only.
  const auto torso = [](float temperature_c, int top) {
    cv::Mat t(192, 256, CV_32F, cv::Scalar(kRoomC));
    cv::ellipse(t, cv::Point(120, top + 60), cv::Size(30, 60), 0, 0, 360, cv::Scalar(temperature_c), cv::FILLED);
    AddNoise(t, 8);
    return t;
  };
  EXPECT_EQ(DetectPersons(cv::Mat(), torso(kClothingC, 30), {}).detections.size(), 1u);
  // The same shape at a laptop lid's or a monitor screen's temperature is an object ...
  EXPECT_TRUE(DetectPersons(cv::Mat(), torso(29.5f, 30), {}).detections.empty());
  EXPECT_TRUE(DetectPersons(cv::Mat(), torso(26.7f, 30), {}).detections.empty());
  PersonDetectorOptions without_rule;
  without_rule.min_top_skin_px = 0;
  EXPECT_EQ(DetectPersons(cv::Mat(), torso(29.5f, 30), without_rule).detections.size(), 1u);
  EXPECT_EQ(DetectPersons(cv::Mat(), torso(26.7f, 30), without_rule).detections.size(), 1u);
  // ... unless the image top cuts it off, where a head may be missing.
  EXPECT_EQ(DetectPersons(cv::Mat(), torso(29.5f, -50), {}).detections.size(), 1u);
}

}  // namespace
}  // namespace hoilcd
