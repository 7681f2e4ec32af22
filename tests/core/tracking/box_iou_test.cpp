#include "hoilcd/core/tracking/box_iou.h"

#include <gtest/gtest.h>

namespace hoilcd {
namespace {

TEST(BoxIoU, IsIntersectionOverUnion) {
  EXPECT_DOUBLE_EQ(BoxIoU(cv::Rect2f(0, 0, 2, 2), cv::Rect2f(1, 0, 2, 2)), 2.0 / 6.0);
  EXPECT_EQ(BoxIoU(cv::Rect2f(0, 0, 2, 2), cv::Rect2f(5, 5, 1, 1)), 0.0);
  EXPECT_EQ(BoxIoU(cv::Rect2f(), cv::Rect2f()), 0.0);
}

}  // namespace
}  // namespace hoilcd
