// How a frame's temperatures become the dataset's image files: the 8-bit thermal PNG (linear over
// the camera's display window) and the 16-bit radiometric PNG (centikelvin). The simulator writes
// through these and readers that re-encode a frame (the report's video check) use the same ones.
#pragma once

#include <opencv2/core.hpp>

#include "hoilcd/core/util/units.h"

namespace hoilcd {

// 8-bit display image: linear over [display_min_c, display_max_c] → [0, 255], clamped, rounded.
cv::Mat ToDisplay8Bit(const cv::Mat& temperature_c, double display_min_c, double display_max_c);

// 16-bit radiometric image (CV_16U): value = temperature in K × 100, rounded, clamped to 0..65535.
cv::Mat ToCentikelvin16(const cv::Mat& temperature_c);
// Its inverse as a reader sees it: CV_32F °C from a CV_16U centikelvin image.
cv::Mat CelsiusFromCentikelvin16(const cv::Mat& centikelvin);

}  // namespace hoilcd
