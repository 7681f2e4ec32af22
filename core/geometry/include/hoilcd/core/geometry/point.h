// The 2-D image point shared by the loop-closure front ends (HOI features, keypoints) and the
// matcher: pixel coordinates, x to the right, y down.
#pragma once

#include <opencv2/core/types.hpp>

namespace hoilcd {

using Point2 = cv::Point2f;

}  // namespace hoilcd
