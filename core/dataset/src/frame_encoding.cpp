#include "hoilcd/core/dataset/frame_encoding.h"

#include "hoilcd/core/util/error.h"

namespace hoilcd {

cv::Mat ToDisplay8Bit(const cv::Mat& temperature_c, double display_min_c, double display_max_c) {
  HOILCD_CHECK(temperature_c.type() == CV_32FC1);
  HOILCD_CHECK_MSG(display_max_c > display_min_c, "display window [" << display_min_c << ", " << display_max_c << "]");
  const double scale = 255.0 / (display_max_c - display_min_c);
  cv::Mat display;
  temperature_c.convertTo(display, CV_8U, scale, -display_min_c * scale);  // saturates, rounds
  return display;
}

cv::Mat ToCentikelvin16(const cv::Mat& temperature_c) {
  HOILCD_CHECK(temperature_c.type() == CV_32FC1);
  cv::Mat centikelvin;
  temperature_c.convertTo(centikelvin, CV_16U, 100.0, kZeroCelsiusK * 100.0);  // saturates, rounds
  return centikelvin;
}

cv::Mat CelsiusFromCentikelvin16(const cv::Mat& centikelvin) {
  HOILCD_CHECK(centikelvin.type() == CV_16UC1);
  cv::Mat celsius;
  centikelvin.convertTo(celsius, CV_32F, 0.01, -kZeroCelsiusK);
  return celsius;
}

}  // namespace hoilcd
