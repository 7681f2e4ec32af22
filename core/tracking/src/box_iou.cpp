#include "hoilcd/core/tracking/box_iou.h"

namespace hoilcd {

double BoxIoU(const cv::Rect2f& a, const cv::Rect2f& b) {
  const double intersection = (a & b).area();
  const double union_area = static_cast<double>(a.area()) + b.area() - intersection;
  return union_area > 0 ? intersection / union_area : 0.0;
}

}  // namespace hoilcd
