#include "hoilcd/core/estimators/homography.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "hoilcd/core/util/random.h"
#include "homography_problems.h"

namespace hoilcd {
namespace {

TEST(HomographyFromFourPoints, ExactCorrespondencesOfRandomHomographyReprojectBelow1e6Px) {
  Rng rng = KeyedRng(1, "test.dlt");
  int solved = 0;
  for (int t = 0; t < 1000; ++t) {
    const Eigen::Matrix3d truth = RandomHomography(rng);
    Point2 src[4], dst[4];
    for (int k = 0; k < 4; ++k) {
      src[k] = RandomPoint(rng);
      dst[k] = Apply(truth, src[k]);
    }
    Eigen::Matrix3d h;
    if (!HomographyFromFourPoints(src, dst, &h)) continue;
    ++solved;
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d p = h * Eigen::Vector3d(src[k].x, src[k].y, 1.0);
      EXPECT_LT(std::hypot(p.x() / p.z() - dst[k].x, p.y() / p.z() - dst[k].y), 1e-6);
    }
  }
  EXPECT_GT(solved, 990);  // only near-collinear random samples are skipped
}

// OpenCV solves the unnormalised 8x8 system and reprojects its own points to about 1e-4 px, so
// the two are compared on where they send points across the image, at 1e-3 px.
TEST(HomographyFromFourPoints, AgreesWithOpenCvGetPerspectiveTransform) {
  Rng rng = KeyedRng(2, "test.dlt");
  for (int t = 0; t < 100; ++t) {
    const Eigen::Matrix3d truth = RandomHomography(rng);
    Point2 src[4], dst[4];
    for (int k = 0; k < 4; ++k) {
      src[k] = RandomPoint(rng);
      dst[k] = Apply(truth, src[k]);
    }
    Eigen::Matrix3d h;
    if (!HomographyFromFourPoints(src, dst, &h)) continue;
    const cv::Mat cv_mat = cv::getPerspectiveTransform(src, dst);
    Eigen::Matrix3d cv_h;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) cv_h(r, c) = cv_mat.at<double>(r, c);
    }
    for (float y = 0; y <= kHeightPx; y += 32) {
      for (float x = 0; x <= kWidthPx; x += 32) {
        const Point2 ours = Apply(h, Point2(x, y)), theirs = Apply(cv_h, Point2(x, y));
        EXPECT_LT(std::hypot(ours.x - theirs.x, ours.y - theirs.y), 1e-3);
      }
    }
  }
}

TEST(HomographyFromFourPoints, DegenerateSamplesAreRejected) {
  const Point2 square[4] = {{10, 10}, {100, 10}, {100, 90}, {10, 90}};
  const Point2 collinear[4] = {{10, 10}, {50, 50}, {90, 90}, {10, 90}};
  const Point2 nearly_collinear[4] = {{10, 10}, {50, 50.0001f}, {90, 90}, {10, 90}};
  const Point2 repeated[4] = {{10, 10}, {10, 10}, {100, 90}, {10, 90}};
  Eigen::Matrix3d h;
  EXPECT_TRUE(HomographyFromFourPoints(square, square, &h));
  EXPECT_TRUE(h.isApprox(Eigen::Matrix3d::Identity(), 1e-12));
  EXPECT_FALSE(HomographyFromFourPoints(collinear, square, &h));
  EXPECT_FALSE(HomographyFromFourPoints(square, collinear, &h));
  EXPECT_FALSE(HomographyFromFourPoints(nearly_collinear, square, &h));
  EXPECT_FALSE(HomographyFromFourPoints(repeated, square, &h));
}

TEST(HomographyLeastSquares, ExactCorrespondencesGiveTheHomographyBack) {
  Rng rng = KeyedRng(3, "test.dlt");
  const Eigen::Matrix3d truth = RandomHomography(rng);
  std::vector<float> rx, ry, qx, qy;
  for (int i = 0; i < 30; ++i) {
    const Point2 r = RandomPoint(rng), q = Apply(truth, r);
    rx.push_back(r.x);
    ry.push_back(r.y);
    qx.push_back(q.x);
    qy.push_back(q.y);
  }
  Eigen::Matrix3d h;
  ASSERT_TRUE(HomographyLeastSquares(rx.data(), ry.data(), qx.data(), qy.data(), nullptr, 30, &h));
  for (int i = 0; i < 30; ++i) {
    const Point2 p = Apply(h, Point2(rx[i], ry[i]));
    EXPECT_LT(std::hypot(p.x - qx[i], p.y - qy[i]), 1e-3);  // inputs are float
  }
}

TEST(HomographyEstimator, CountInliersIsTheMarkedCountAtEveryLengthAndStopsOnlyAtOrBelowTheBar) {
  Rng rng = KeyedRng(6, "test.dlt");
  for (int n = 4; n <= 40; ++n) {  // every remainder of the eight-lane steps
    const HomographyProblem p = MakeHomographyProblem(rng, n, n / 2, 1.0);
    std::vector<float> rx, ry, qx, qy, quads;
    for (int i = 0; i < n; ++i) {
      rx.push_back(p.reference[i].x);
      ry.push_back(p.reference[i].y);
      qx.push_back(p.query[i].x);
      qy.push_back(p.query[i].y);
    }
    const HomographyEstimator::Data data =
        HomographyEstimator::Prepare(rx.data(), ry.data(), qx.data(), qy.data(), n, &quads);
    const Eigen::Matrix3d& h = p.reference_to_query;
    float model[9];
    for (int k = 0; k < 9; ++k) model[k] = static_cast<float>(h(k / 3, k % 3) / h.cwiseAbs().maxCoeff());
    std::vector<uint8_t> mask(n);
    HomographyEstimator::MarkInliers(model, data, 25.0f, mask.data());
    const int marked = static_cast<int>(std::count(mask.begin(), mask.end(), 1));
    EXPECT_EQ(HomographyEstimator::CountInliers(model, data, 25.0f, -1), marked) << n;
    for (int bar = 0; bar <= n; ++bar) {
      const int counted = HomographyEstimator::CountInliers(model, data, 25.0f, bar);
      if (marked > bar) {
        EXPECT_EQ(counted, marked) << n << " " << bar;
      } else {
        EXPECT_LE(counted, bar) << n << " " << bar;
      }
    }
  }
}

}  // namespace
}  // namespace hoilcd
