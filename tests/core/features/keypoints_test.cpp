#include "hoilcd/core/features/keypoints.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "option_properties.h"

namespace hoilcd {
namespace {

// A dark image with a bright triangle and a rectangle, slightly blurred like a thermal frame:
// their corners are the keypoints.
const std::vector<cv::Point> kTriangle = {{40, 50}, {110, 70}, {60, 120}};
cv::Mat Rectangles() {
  cv::Mat image(192, 256, CV_8U, cv::Scalar(40));
  cv::fillConvexPoly(image, kTriangle, cv::Scalar(220));
  cv::rectangle(image, cv::Rect(150, 100, 50, 60), cv::Scalar(180), cv::FILLED);
  cv::GaussianBlur(image, image, cv::Size(), 0.8);
  return image;
}

TEST(Keypoints, EveryDetectorFindsTheRectangleCornersAndRespectsBorderAndRadius) {
  for (const char* detector : {"gftt", "fast", "orb", "sift", "akaze"}) {
    KeypointOptions options;
    options.detector = detector;
    const std::vector<Point2> points = DetectKeypoints(Rectangles(), options);
    ASSERT_FALSE(points.empty()) << detector;
    int near_corner = 0;
    for (const Point2& p : points) {
      EXPECT_GE(p.x, options.border_px) << detector;
      EXPECT_GE(p.y, options.border_px) << detector;
      EXPECT_LT(p.x, 256 - options.border_px) << detector;
      for (const cv::Point& c : kTriangle) {
        if (cv::norm(p - cv::Point2f(c)) < 5.0) {
          ++near_corner;
          break;
        }
      }
    }
    // Corner detectors fire at the corners; blob detectors (SIFT, AKAZE) at least on the shapes.
    const bool corner_detector =
        std::string(detector) == "gftt" || std::string(detector) == "fast" || std::string(detector) == "orb";
    if (corner_detector) {
      EXPECT_GE(near_corner, 2) << detector;
    }
    for (const Point2& p : points) {
      const bool on_shape = cv::Rect(30, 40, 90, 90).contains(p) || cv::Rect(140, 90, 70, 80).contains(p);
      EXPECT_TRUE(on_shape) << detector << " " << p;
    }
    if (std::string(detector) != "gftt") {
      for (size_t i = 0; i < points.size(); ++i)
        for (size_t j = i + 1; j < points.size(); ++j)
          EXPECT_GE(cv::norm(points[i] - points[j]), options.nms_radius_px - 1e-6) << detector;
    }
  }
}

TEST(Keypoints, UniformImageHasNoKeypointsAndMaxIsRespected) {
  KeypointOptions options;
  EXPECT_TRUE(DetectKeypoints(cv::Mat(192, 256, CV_8U, cv::Scalar(90)), options).empty());
  options.max_keypoints = 3;
  EXPECT_LE(DetectKeypoints(Rectangles(), options).size(), 3u);
}

TEST(Keypoints, CheckRejectsUnknownDetector) {
  KeypointOptions options;
  options.detector = "superpoint";
  EXPECT_EQ(options.Check(), "detector: must be one of: gftt, fast, orb, sift, akaze (got 'superpoint')");
  EXPECT_THROW(DetectKeypoints(Rectangles(), options), std::logic_error);
}

TEST(Keypoints, OptionsHoldSuperPointLikeDefaultsFromTheirTableAndEveryBoundIsChecked) {
  const KeypointOptions options;
  EXPECT_EQ(options.detector, "gftt");
  EXPECT_EQ(options.max_keypoints, 1000);
  EXPECT_EQ(options.nms_radius_px, 4.0);
  EXPECT_EQ(options.border_px, 4);
  ExpectConstructedHoldsTheTableDefaults<KeypointOptions>();
  EXPECT_EQ(ExpectEveryBoundCrossedIsNamedByCheck<KeypointOptions>(), 13);
}

}  // namespace
}  // namespace hoilcd

namespace hoilcd {
namespace {

TEST(Keypoints, GfttIgnoresSensorNoiseOnAUniformWallButKeepsRealCorners) {
  cv::Mat wall(192, 256, CV_8U);
  cv::randn(wall, 60, 0.6);  // ~0.02 K of noise in a 20-30 °C window, the fixed pattern alike
  KeypointOptions options;
  EXPECT_TRUE(DetectKeypoints(wall, options).empty());
  options.gftt_min_eigenvalue = 0;  // GFTT's relative quality alone fires on the noise
  EXPECT_GT(DetectKeypoints(wall, options).size(), 100u);
  cv::Mat scene = wall.clone();
  cv::rectangle(scene, cv::Rect(100, 80, 40, 30), cv::Scalar(160), cv::FILLED);
  cv::GaussianBlur(scene, scene, cv::Size(), 0.8);
  const auto corners = DetectKeypoints(scene, KeypointOptions{});
  EXPECT_GE(corners.size(), 4u);
  EXPECT_LE(corners.size(), 12u);
}

}  // namespace
}  // namespace hoilcd
