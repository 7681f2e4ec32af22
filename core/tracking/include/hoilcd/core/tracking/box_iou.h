// Overlap of two axis-aligned boxes: the one IoU that ByteTrack's continuous convention, the
// tracking metrics and the detection tool all use.
#pragma once

#include <opencv2/core.hpp>

namespace hoilcd {

// Intersection over union of two boxes (0 when the union is empty).
double BoxIoU(const cv::Rect2f& a, const cv::Rect2f& b);

}  // namespace hoilcd
