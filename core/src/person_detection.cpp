#include "hoilcd/core/person_detection.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "hoilcd/core/error.h"

namespace hoilcd {

std::string PersonDetectorOptions::Check() const {
  std::ostringstream out;
  const auto need = [&out](bool ok, const char* what, double value) {
    if (!ok) out << what << ", got " << value << "; ";
  };
  need(std::isfinite(threshold_c), "threshold_c must be finite", threshold_c);
  need(threshold_u8 >= 0 && threshold_u8 <= 255, "threshold_u8 must be in [0, 255]", threshold_u8);
  need(u8_max_c > u8_min_c, "u8_max_c must exceed u8_min_c", u8_max_c);
  need(open_kernel_px >= 0, "open_kernel_px must be >= 0", open_kernel_px);
  need(close_kernel_px >= 0, "close_kernel_px must be >= 0", close_kernel_px);
  need(profile_smooth_px >= 1, "profile_smooth_px must be >= 1", profile_smooth_px);
  need(split_valley_ratio > 0 && split_valley_ratio < 1, "split_valley_ratio must be in (0, 1)",
       split_valley_ratio);
  need(valley_tolerance_ratio >= 0 && valley_tolerance_ratio < 1,
       "valley_tolerance_ratio must be in [0, 1)", valley_tolerance_ratio);
  need(min_peak_ratio >= 0 && min_peak_ratio <= 1, "min_peak_ratio must be in [0, 1]",
       min_peak_ratio);
  need(min_split_width_px >= 1, "min_split_width_px must be >= 1", min_split_width_px);
  need(min_area_px >= 1, "min_area_px must be >= 1", min_area_px);
  need(min_height_px >= 1, "min_height_px must be >= 1", min_height_px);
  need(min_aspect_hw > 0 && min_aspect_hw < max_aspect_hw,
       "need 0 < min_aspect_hw < max_aspect_hw; min_aspect_hw", min_aspect_hw);
  need(max_median_c > threshold_c, "max_median_c must exceed threshold_c", max_median_c);
  need(max_hot_fraction > 0 && max_hot_fraction <= 1, "max_hot_fraction must be in (0, 1]",
       max_hot_fraction);
  need(max_fill_ratio > 0 && max_fill_ratio <= 1, "max_fill_ratio must be in (0, 1]",
       max_fill_ratio);
  need(max_flat_top_fraction > 0 && max_flat_top_fraction <= 1, "max_flat_top_fraction must be in (0, 1]",
       max_flat_top_fraction);
  need(max_solidity > 0 && max_solidity <= 1, "max_solidity must be in (0, 1]", max_solidity);
  need(score_area_px > 0, "score_area_px must be > 0", score_area_px);
  need(typical_aspect_hw > 0, "typical_aspect_hw must be > 0", typical_aspect_hw);
  need(aspect_sigma_log > 0, "aspect_sigma_log must be > 0", aspect_sigma_log);
  need(person_max_c >= person_min_c, "person_max_c must be >= person_min_c", person_max_c);
  need(temperature_sigma_c > 0, "temperature_sigma_c must be > 0", temperature_sigma_c);
  std::string message = out.str();
  if (!message.empty()) message.resize(message.size() - 2);
  return message;
}

// Seated neighbours touch at shoulders or arms, but each has a head on top: the per-column pixel
// count has one peak per person with a valley between. We split recursively at the deepest valley
// (relative to the lower of its two flanking peaks) while it is deep enough and both peaks are
// tall enough to be people, cutting in the middle of the valley floor. Chosen over
// distance-transform peaks because touching torsos of equal width give one ridge there, not two
// maxima.
std::vector<int> FindSplitColumns(const std::vector<double>& column_counts,
                                  const PersonDetectorOptions& options) {
  const int n = static_cast<int>(column_counts.size());
  std::vector<double> p(n, 0.0);
  const int half = options.profile_smooth_px / 2;
  for (int c = 0; c < n; ++c) {
    const int lo = std::max(0, c - half), hi = std::min(n - 1, c + half);
    double sum = 0;
    for (int k = lo; k <= hi; ++k) sum += column_counts[k];
    p[c] = sum / (hi - lo + 1);
  }
  const double global_max = n > 0 ? *std::max_element(p.begin(), p.end()) : 0.0;
  std::vector<int> splits;
  if (global_max <= 0) return splits;
  const int min_width = options.min_split_width_px;
  const double min_peak = options.min_peak_ratio * global_max;

  std::function<void(int, int)> split = [&](int a, int b) {
    if (b - a < 2 * min_width) return;
    std::vector<double> left_max(b - a), right_max(b - a);
    for (int c = a; c < b; ++c) left_max[c - a] = std::max(p[c], c > a ? left_max[c - a - 1] : 0.0);
    for (int c = b - 1; c >= a; --c) {
      right_max[c - a] = std::max(p[c], c < b - 1 ? right_max[c - a + 1] : 0.0);
    }
    int best_m = -1;
    double best_ratio = std::numeric_limits<double>::infinity(), best_peak = 0;
    for (int m = a + min_width; m <= b - min_width; ++m) {
      const double lower_peak = std::min(left_max[m - a], right_max[m - a]);
      if (lower_peak < min_peak) continue;
      const double ratio = p[m] / lower_peak;
      if (ratio <= options.split_valley_ratio && ratio < best_ratio) {
        best_ratio = ratio;
        best_m = m;
        best_peak = lower_peak;
      }
    }
    if (best_m < 0) return;
    // The valley floor: neighbouring columns within the tolerance of the deepest one; split in
    // its middle (where two torsos of slightly different heights meet).
    const double floor_limit = p[best_m] + options.valley_tolerance_ratio * best_peak;
    int lo = best_m, hi = best_m;
    while (lo - 1 > a && p[lo - 1] <= floor_limit) --lo;
    while (hi + 1 < b && p[hi + 1] <= floor_limit) ++hi;
    const int m = std::clamp((lo + hi + 1) / 2, a + min_width, b - min_width);
    split(a, m);
    splits.push_back(m);
    split(m, b);
  };
  split(0, n);
  std::sort(splits.begin(), splits.end());
  return splits;
}

namespace {

cv::Mat Ellipse(int diameter_px) {
  return cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(diameter_px, diameter_px));
}

struct PartStats {
  int area = 0;
  cv::Rect box;  // tight, integer pixels
  std::vector<float> temperatures_c;
};

double Score(const PartStats& part, double median_c, const PersonDetectorOptions& options) {
  const double area_score = 1.0 - std::exp(-part.area / options.score_area_px);
  const double aspect = static_cast<double>(part.box.height) / part.box.width;
  const double log_ratio = std::log(aspect / options.typical_aspect_hw) / options.aspect_sigma_log;
  const double shape_score = std::exp(-0.5 * log_ratio * log_ratio);
  const double outside_c = std::max({0.0, options.person_min_c - median_c,
                                     median_c - options.person_max_c});
  const double z = outside_c / options.temperature_sigma_c;
  const double temperature_score = std::exp(-0.5 * z * z);
  const double score = std::cbrt(area_score * shape_score * temperature_score);
  return std::clamp(score, 1e-3, 1.0);
}

}  // namespace

PersonDetections DetectPersons(const cv::Mat& thermal_u8, const cv::Mat& radiometric_c,
                               const PersonDetectorOptions& options) {
  const std::string problem = options.Check();
  HOILCD_CHECK_MSG(problem.empty(), problem);
  HOILCD_CHECK_MSG(!thermal_u8.empty() || !radiometric_c.empty(), "no image given");
  HOILCD_CHECK(thermal_u8.empty() || thermal_u8.type() == CV_8UC1);
  HOILCD_CHECK(radiometric_c.empty() || radiometric_c.type() == CV_32FC1);
  HOILCD_CHECK(thermal_u8.empty() || radiometric_c.empty() ||
               thermal_u8.size() == radiometric_c.size());

  cv::Mat mask, temperature_c;
  if (!radiometric_c.empty()) {
    mask = radiometric_c >= options.threshold_c;
    temperature_c = radiometric_c;
  } else {
    mask = thermal_u8 >= options.threshold_u8;
    thermal_u8.convertTo(temperature_c, CV_32F, (options.u8_max_c - options.u8_min_c) / 255.0,
                         options.u8_min_c);
  }
  if (options.open_kernel_px > 1) {
    cv::morphologyEx(mask, mask, cv::MORPH_OPEN, Ellipse(options.open_kernel_px));
  }
  if (options.close_kernel_px > 1) {
    cv::morphologyEx(mask, mask, cv::MORPH_CLOSE, Ellipse(options.close_kernel_px));
  }

  cv::Mat labels, stats, centroids;
  const int num_labels =
      cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  PersonDetections result;
  result.mask = cv::Mat::zeros(mask.size(), CV_8U);
  for (int label = 1; label < num_labels; ++label) {
    const cv::Rect blob(
        stats.at<int>(label, cv::CC_STAT_LEFT), stats.at<int>(label, cv::CC_STAT_TOP),
        stats.at<int>(label, cv::CC_STAT_WIDTH), stats.at<int>(label, cv::CC_STAT_HEIGHT));
    if (stats.at<int>(label, cv::CC_STAT_AREA) < options.min_area_px) continue;
    std::vector<double> counts(blob.width, 0.0);
    for (int y = blob.y; y < blob.br().y; ++y) {
      const int* row = labels.ptr<int>(y);
      for (int x = blob.x; x < blob.br().x; ++x) counts[x - blob.x] += row[x] == label;
    }
    std::vector<int> bounds = FindSplitColumns(counts, options);
    bounds.insert(bounds.begin(), 0);
    bounds.push_back(blob.width);

    for (size_t k = 0; k + 1 < bounds.size(); ++k) {
      const int x0 = blob.x + bounds[k], x1 = blob.x + bounds[k + 1];
      PartStats part;
      int min_x = x1, max_x = x0 - 1, min_y = blob.br().y, max_y = blob.y - 1;
      for (int y = blob.y; y < blob.br().y; ++y) {
        const int* row = labels.ptr<int>(y);
        const float* t_row = temperature_c.ptr<float>(y);
        for (int x = x0; x < x1; ++x) {
          if (row[x] != label) continue;
          ++part.area;
          min_x = std::min(min_x, x);
          max_x = std::max(max_x, x);
          min_y = std::min(min_y, y);
          max_y = std::max(max_y, y);
          part.temperatures_c.push_back(t_row[x]);
        }
      }
      if (part.area < options.min_area_px) continue;
      part.box = cv::Rect(min_x, min_y, max_x - min_x + 1, max_y - min_y + 1);
      if (part.box.height < options.min_height_px) continue;
      const double aspect = static_cast<double>(part.box.height) / part.box.width;
      if (aspect < options.min_aspect_hw || aspect > options.max_aspect_hw) continue;
      auto middle = part.temperatures_c.begin() + part.temperatures_c.size() / 2;
      std::nth_element(part.temperatures_c.begin(), middle, part.temperatures_c.end());
      const double median_c = *middle;
      if (median_c > options.max_median_c) continue;
      // 1e-3 degC absorbs the rounding of 255 -> u8_max_c in the 8-bit conversion.
      const auto hot = std::count_if(part.temperatures_c.begin(), part.temperatures_c.end(),
                                     [&](float t) { return t >= options.hot_c - 1e-3; });
      if (static_cast<double>(hot) > options.max_hot_fraction * part.area) continue;

      // Rectangular and convex together means a manufactured object (laptop, screen, radiator).
      const cv::Mat part_mask = (labels(part.box) == label);
      std::vector<cv::Point> points, hull;
      cv::findNonZero(part_mask, points);
      cv::convexHull(points, hull);
      cv::Mat hull_mask = cv::Mat::zeros(part.box.size(), CV_8U);
      cv::fillConvexPoly(hull_mask, hull, cv::Scalar(255));
      const double solidity = part.area / static_cast<double>(cv::countNonZero(hull_mask));
      const double fill = part.area / static_cast<double>(part.box.area());
      if (fill >= options.max_fill_ratio && solidity >= options.max_solidity) continue;
      if (part.box.y > 0) {  // a straight top edge is a screen, not a head
        std::vector<int> tops;
        for (int x = 0; x < part_mask.cols; ++x) {
          for (int y = 0; y < part_mask.rows; ++y) {
            if (part_mask.at<uint8_t>(y, x)) {
              tops.push_back(y);
              break;
            }
          }
        }
        std::vector<int> sorted = tops;
        std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
        const int median_top = sorted[sorted.size() / 2];
        const auto flat = std::count_if(tops.begin(), tops.end(), [&](int y) { return std::abs(y - median_top) <= 1; });
        if (static_cast<double>(flat) > options.max_flat_top_fraction * tops.size()) continue;
      }

      result.mask(part.box).setTo(255, part_mask);
      result.detections.push_back(
          {cv::Rect2f(part.box), static_cast<float>(Score(part, median_c, options))});
    }
  }
  return result;
}

}  // namespace hoilcd
