#include "hoilcd/core/keypoints.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

namespace hoilcd {
namespace {

// A dark image with bright rectangles: their corners are the keypoints.
cv::Mat Rectangles() {
  cv::Mat image(192, 256, CV_8U, cv::Scalar(40));
  cv::rectangle(image, cv::Rect(40, 50, 60, 40), cv::Scalar(220), cv::FILLED);
  cv::rectangle(image, cv::Rect(150, 100, 50, 60), cv::Scalar(180), cv::FILLED);
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
      for (const cv::Point2f c : {cv::Point2f(40, 50), cv::Point2f(99, 50), cv::Point2f(40, 89),
                                  cv::Point2f(99, 89)}) {
        if (cv::norm(p - c) < 4.0) {
          ++near_corner;
          break;
        }
      }
    }
    EXPECT_GE(near_corner, 2) << detector;
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
  EXPECT_NE(options.Check().find("gftt"), std::string::npos);
  EXPECT_THROW(DetectKeypoints(Rectangles(), options), std::logic_error);
}

}  // namespace
}  // namespace hoilcd
