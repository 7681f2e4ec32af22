#include "hoilcd/core/features/person_detection.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include <opencv2/imgproc.hpp>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/sizes.h"
#include "hoilcd/core/util/stats.h"

namespace hoilcd {

PersonDetectorOptions::PersonDetectorOptions() { Table().FillDefaults(this); }

const OptionTable<PersonDetectorOptions>& PersonDetectorOptions::Table() {
  using O = PersonDetectorOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          // Thresholding and clean-up.
          .Add("threshold_c", &O::threshold_c, 26.5, "degC", R::Any(),
               "person threshold of the detector (on an 8-bit frame alone, the first level at or above it)")
          .Add("u8_min_c", &O::u8_min_c, 20, "degC", R::Any(),
               "shown as 0 in the 8-bit frame (the manifest's window_min_c)")
          .Add("u8_max_c", &O::u8_max_c, 30, "degC", R::Any(),
               "shown as 255 in the 8-bit frame (the manifest's window_max_c)")
          .Rule("u8_max_c", [](const O& o) { return o.u8_max_c > o.u8_min_c ? "" : "must exceed u8_min_c"; })
          // Speckle and holes are a few pixels; a kernel as wide as a seated person (~30 px at
          // 256 x 192) erases people, and its cost grows with its area.
          .Add("open_kernel_px", &O::open_kernel_px, 3, "px", R::Closed(0, 31),
               "elliptic opening diameter that removes speckle (0: none)")
          .Add("close_kernel_px", &O::close_kernel_px, 5, "px", R::Closed(0, 31),
               "elliptic closing diameter that fills small holes (0: none)")
          // Splitting touching neighbours.
          .Add("profile_smooth_px", &O::profile_smooth_px, 3, "px", R::Closed(1, kMaxImageSidePx),
               "box-filter width over the per-column pixel counts")
          .Add("split_valley_ratio", &O::split_valley_ratio, 0.85, "", R::Any().Above(0).Below(1),
               "split at a valley at most this fraction of the lower peak")
          .Add("valley_tolerance_ratio", &O::valley_tolerance_ratio, 0.1, "", R::Any().AtLeast(0).Below(1),
               "of the lower peak; the valley floor is cut in its middle")
          .Add("min_peak_ratio", &O::min_peak_ratio, 0.5, "", R::Closed(0, 1),
               "a peak is a person only if at least this fraction of the blob's maximum")
          .Add("min_split_width_px", &O::min_split_width_px, 8, "px", R::Closed(1, kMaxImageSidePx),
               "every part of a split is at least this wide")
          // Head seeds.
          .Add("head_min_c", &O::head_min_c, 31.0, "degC", R::Any(), "lowest skin temperature of a head seed")
          .Add("min_head_area_px", &O::min_head_area_px, 10, "px^2", R::Any().AtLeast(1),
               "smaller skin spots are ignored")
          .Add("head_zone_ratio", &O::head_zone_ratio, 0.8, "", R::Any().Above(0).AtMost(1),
               "a head's top lies in this upper fraction of its blob")
          .Add("merge_min_overlap", &O::merge_min_overlap, 0.5, "", R::Any().Above(0).AtMost(1),
               "column overlap, of the headless part's width, for it to join a part with a head")
          .Add("min_fragment_area_px", &O::min_fragment_area_px, 6, "px^2", R::Any().AtLeast(1),
               "smaller parts are dropped before merging")
          // Rejection of non-people.
          .Add("min_area_px", &O::min_area_px, 60, "px^2", R::Any().AtLeast(1), "smaller parts are not people")
          .Add("min_height_px", &O::min_height_px, 12, "px", R::Any().AtLeast(1), "lower parts are not people")
          .Add("min_aspect_hw", &O::min_aspect_hw, 0.6, "", R::Any().Above(0),
               "height/width; flatter parts are laptops, radiators, tables")
          .Add("max_aspect_hw", &O::max_aspect_hw, 5.0, "", R::Any(),
               "height/width; taller parts are pipes or door frames")
          .Rule("min_aspect_hw",
                [](const O& o) { return o.min_aspect_hw < o.max_aspect_hw ? "" : "must be below max_aspect_hw"; })
          .Add("max_median_c", &O::max_median_c, 37.0, "degC", R::Any(),
               "hotter parts are cups (> 40) or radiators (~40)")
          .Rule("max_median_c",
                [](const O& o) { return o.max_median_c > o.threshold_c ? "" : "must exceed threshold_c"; })
          .Add("hot_c", &O::hot_c, 30, "degC", R::Any(), "the 8-bit image saturates here (u8_max_c)")
          .Add("max_hot_fraction", &O::max_hot_fraction, 0.7, "", R::Any().Above(0).AtMost(1),
               "parts with more pixels at or above hot_c are laptops, cups, radiators")
          .Add("max_fill_ratio", &O::max_fill_ratio, 0.9, "", R::Any().Above(0).AtMost(1),
               "area / box area; rectangles fill more ...")
          .Add("max_solidity", &O::max_solidity, 0.97, "", R::Any().Above(0).AtMost(1),
               "... and are convex (area / hull area): both make an object")
          .Add("max_flat_top_fraction", &O::max_flat_top_fraction, 0.7, "", R::Any().Above(0).AtMost(1),
               "of a part's columns whose top pixel lies within 1 px of the median top row; flatter tops are screens")
          // Skin or clothing (radiometric frames only).
          .Add("min_top_skin_px", &O::min_top_skin_px, 10, "px^2", R::Any().AtLeast(0),
               "skin pixels needed in the top zone (0: rule off)")
          .Add("top_skin_zone_ratio", &O::top_skin_zone_ratio, 0.33, "", R::Any().Above(0).AtMost(1),
               "upper fraction of the part's box height: the top zone")
          .Add("clothing_min_c", &O::clothing_min_c, 27.0, "degC", R::Any(),
               "lowest apparent temperature counted as clothing")
          .Add("clothing_max_c", &O::clothing_max_c, 29.0, "degC", R::Any(),
               "highest apparent temperature counted as clothing")
          .Rule("clothing_max_c",
                [](const O& o) { return o.clothing_max_c > o.clothing_min_c ? "" : "must exceed clothing_min_c"; })
          .Add("min_clothing_fraction", &O::min_clothing_fraction, 0.6, "", R::Closed(0, 1),
               "of a part's pixels at clothing temperature, when it shows no skin")
          // Score.
          .Add("score_area_px", &O::score_area_px, 400, "px^2", R::Any().Above(0),
               "area at which the area score is 1 - 1/e")
          .Add("typical_aspect_hw", &O::typical_aspect_hw, 1.8, "", R::Any().Above(0),
               "height/width of a seated person, shape score 1")
          .Add("aspect_sigma_log", &O::aspect_sigma_log, 0.7, "", R::Any().Above(0),
               "width of the shape score, natural-log units")
          .Add("person_min_c", &O::person_min_c, 27, "degC", R::Any(),
               "a median below this lowers the temperature score")
          .Add("person_max_c", &O::person_max_c, 35, "degC", R::Any(),
               "a median above this lowers the temperature score")
          .Rule("person_max_c",
                [](const O& o) { return o.person_max_c >= o.person_min_c ? "" : "must be at least person_min_c"; })
          .Add("temperature_sigma_c", &O::temperature_sigma_c, 2, "degC", R::Any().Above(0),
               "fall-off of the temperature score outside its range");
  return table;
}

std::string PersonDetectorOptions::Check() const { return Table().FirstProblem(*this); }

// Seated neighbours touch at shoulders or arms, but each has a head on top: the per-column pixel
// count has one peak per person with a valley between. We split recursively at the deepest valley
// (relative to the lower of its two flanking peaks) while it is deep enough and both peaks are
// tall enough to be people, cutting in the middle of the valley floor. Chosen over
// distance-transform peaks because touching torsos of equal width give one ridge there, not two
// maxima.
std::vector<int> FindSplitColumns(const std::vector<double>& column_counts, const PersonDetectorOptions& options) {
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

struct Part {
  cv::Rect box;  // tight, integer pixels
  std::vector<cv::Point> pixels;
  std::vector<float> temperatures_c;
  bool has_head = false;
};

struct ColumnSpan {
  int x0 = 0, x1 = 0;  // [x0, x1) within the blob
};

// Skin-temperature components in the upper part of the blob, merged where they share columns
// (a face and an ear, or two heads one behind the other that columns cannot separate anyway).
std::vector<ColumnSpan> FindHeads(const cv::Mat& labels, int label, const cv::Rect& blob, const cv::Mat& temperature_c,
                                  const PersonDetectorOptions& options) {
  const cv::Mat skin = (labels(blob) == label) & (temperature_c(blob) >= options.head_min_c) &
                       (temperature_c(blob) <= options.max_median_c);
  cv::Mat skin_labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(skin, skin_labels, stats, centroids, 8, CV_32S);
  std::vector<ColumnSpan> heads;
  for (int k = 1; k < n; ++k) {
    if (stats.at<int>(k, cv::CC_STAT_AREA) < options.min_head_area_px) continue;
    if (stats.at<int>(k, cv::CC_STAT_TOP) > options.head_zone_ratio * blob.height) continue;
    const int x0 = stats.at<int>(k, cv::CC_STAT_LEFT);
    heads.push_back({x0, x0 + stats.at<int>(k, cv::CC_STAT_WIDTH)});
  }
  std::sort(heads.begin(), heads.end(), [](const ColumnSpan& a, const ColumnSpan& b) { return a.x0 < b.x0; });
  std::vector<ColumnSpan> merged;
  for (const ColumnSpan& h : heads) {
    if (!merged.empty()) {
      ColumnSpan& last = merged.back();
      const int overlap = std::min(last.x1, h.x1) - std::max(last.x0, h.x0);
      if (2 * overlap >= std::min(last.x1 - last.x0, h.x1 - h.x0)) {
        last.x1 = std::max(last.x1, h.x1);
        continue;
      }
    }
    merged.push_back(h);
  }
  return merged;
}

// Between neighbouring heads: the middle of the gap between them, or of their centres when
// they overlap a little.
std::vector<int> SplitBetweenHeads(const std::vector<ColumnSpan>& heads) {
  std::vector<int> splits;
  for (size_t k = 0; k + 1 < heads.size(); ++k) {
    const ColumnSpan& a = heads[k];
    const ColumnSpan& b = heads[k + 1];
    const int m = b.x0 >= a.x1 ? (a.x1 + b.x0 + 1) / 2 : (a.x0 + a.x1 + b.x0 + b.x1 + 2) / 4;
    if (splits.empty() || m > splits.back()) splits.push_back(m);
  }
  return splits;
}

// Warm objects: too hot overall, mostly above clothing temperature, or a filled convex
// rectangle (laptop, screen, radiator).
bool IsObject(const Part& part, double median_c, const PersonDetectorOptions& options) {
  if (median_c > options.max_median_c) return true;
  // 1e-3 degC absorbs the rounding of 255 -> u8_max_c in the 8-bit conversion.
  const auto hot = std::count_if(part.temperatures_c.begin(), part.temperatures_c.end(),
                                 [&](float t) { return t >= options.hot_c - 1e-3; });
  const double area = static_cast<double>(part.pixels.size());
  if (static_cast<double>(hot) > options.max_hot_fraction * area) return true;
  std::vector<cv::Point> hull;
  cv::convexHull(part.pixels, hull);
  for (cv::Point& q : hull) q -= part.box.tl();
  cv::Mat hull_mask = cv::Mat::zeros(part.box.size(), CV_8U);
  cv::fillConvexPoly(hull_mask, hull, cv::Scalar(255));
  const double solidity = area / cv::countNonZero(hull_mask);
  const double fill = area / part.box.area();
  if (fill >= options.max_fill_ratio && solidity >= options.max_solidity) return true;
  // A straight top edge is a screen, not a head (parts touching the image top are exempt).
  if (part.has_head || part.box.y == 0 || part.box.width < 1) return false;
  std::vector<int> tops(part.box.width, std::numeric_limits<int>::max());
  for (const cv::Point& q : part.pixels) {
    int& top = tops[q.x - part.box.x];
    top = std::min(top, q.y);
  }
  std::vector<int> sorted = tops;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const int median_top = sorted[sorted.size() / 2];
  const auto flat = std::count_if(tops.begin(), tops.end(), [&](int y) { return std::abs(y - median_top) <= 1; });
  return static_cast<double>(flat) > options.max_flat_top_fraction * tops.size();
}

// A face, neck or ears near the top of the part's box, or (a person seen from behind) mostly
// clothing; parts cut off by the image top may have lost their head and pass too.
bool LooksHuman(const Part& part, const PersonDetectorOptions& options) {
  if (part.box.y == 0) return true;
  const double zone_end_y = part.box.y + options.top_skin_zone_ratio * part.box.height;
  int skin = 0, clothing = 0;
  for (size_t k = 0; k < part.pixels.size(); ++k) {
    const float t = part.temperatures_c[k];
    skin += part.pixels[k].y < zone_end_y && t >= options.head_min_c && t <= options.max_median_c;
    clothing += t >= options.clothing_min_c && t <= options.clothing_max_c;
  }
  return skin >= options.min_top_skin_px ||
         clothing >= options.min_clothing_fraction * static_cast<double>(part.pixels.size());
}

double Score(const Part& part, double median_c, const PersonDetectorOptions& options) {
  const double area = static_cast<double>(part.pixels.size());
  const double area_score = 1.0 - std::exp(-area / options.score_area_px);
  const double aspect = static_cast<double>(part.box.height) / part.box.width;
  const double log_ratio = std::log(aspect / options.typical_aspect_hw) / options.aspect_sigma_log;
  const double shape_score = std::exp(-0.5 * log_ratio * log_ratio);
  const double outside_c = std::max({0.0, options.person_min_c - median_c, median_c - options.person_max_c});
  const double z = outside_c / options.temperature_sigma_c;
  const double temperature_score = std::exp(-0.5 * z * z);
  const double score = std::cbrt(area_score * shape_score * temperature_score);
  return std::clamp(score, 1e-3, 1.0);
}

// The part with a head that a headless part joins: it must lie lower (its top below the head
// part's top) and share enough of its columns; the largest overlap wins. -1 when none.
int HostOf(const Part& headless, const std::vector<Part>& parts, const PersonDetectorOptions& options) {
  int host = -1, best_overlap = 0;
  for (size_t k = 0; k < parts.size(); ++k) {
    const Part& p = parts[k];
    if (!p.has_head || headless.box.y <= p.box.y) continue;
    const int overlap = std::min(p.box.br().x, headless.box.br().x) - std::max(p.box.x, headless.box.x);
    if (overlap < options.merge_min_overlap * headless.box.width) continue;
    if (overlap > best_overlap) {
      best_overlap = overlap;
      host = static_cast<int>(k);
    }
  }
  return host;
}

// The warm mask (at or above threshold_c, opened and closed) and the temperatures it came from
// (radiometric, or read back from the 8-bit frame through the display window).
void WarmMask(const cv::Mat& thermal_u8, const cv::Mat& radiometric_c, const PersonDetectorOptions& options,
              cv::Mat* mask, cv::Mat* temperature_c) {
  if (!radiometric_c.empty()) {
    *mask = radiometric_c >= options.threshold_c;
    *temperature_c = radiometric_c;
  } else {
    // Level v shows u8_min_c + v * (u8_max_c - u8_min_c) / 255 degC: the first at or above
    // threshold_c (256: none is).
    const double level =
        std::ceil((options.threshold_c - options.u8_min_c) / (options.u8_max_c - options.u8_min_c) * 255.0);
    *mask = thermal_u8 >= std::clamp(level, 0.0, 256.0);
    thermal_u8.convertTo(*temperature_c, CV_32F, (options.u8_max_c - options.u8_min_c) / 255.0, options.u8_min_c);
  }
  if (options.open_kernel_px > 1) {
    cv::morphologyEx(*mask, *mask, cv::MORPH_OPEN, Ellipse(options.open_kernel_px));
  }
  if (options.close_kernel_px > 1) {
    cv::morphologyEx(*mask, *mask, cv::MORPH_CLOSE, Ellipse(options.close_kernel_px));
  }
}

// One connected blob split into column parts (between heads, or at valleys of its column
// profile when it has none); warm objects and specks dropped.
void SplitBlob(const cv::Mat& labels, int label, const cv::Rect& blob, const cv::Mat& temperature_c,
               const PersonDetectorOptions& options, std::vector<Part>* parts) {
  const std::vector<ColumnSpan> heads = FindHeads(labels, label, blob, temperature_c, options);
  std::vector<int> bounds;
  if (heads.size() >= 2) {
    bounds = SplitBetweenHeads(heads);
  } else if (heads.empty()) {
    std::vector<double> counts(blob.width, 0.0);
    for (int y = blob.y; y < blob.br().y; ++y) {
      const int* row = labels.ptr<int>(y);
      for (int x = blob.x; x < blob.br().x; ++x) counts[x - blob.x] += row[x] == label;
    }
    bounds = FindSplitColumns(counts, options);
  }
  bounds.insert(bounds.begin(), 0);
  bounds.push_back(blob.width);
  for (size_t k = 0; k + 1 < bounds.size(); ++k) {
    const int x0 = blob.x + bounds[k], x1 = blob.x + bounds[k + 1];
    Part part;
    for (int y = blob.y; y < blob.br().y; ++y) {
      const int* row = labels.ptr<int>(y);
      const float* t_row = temperature_c.ptr<float>(y);
      for (int x = x0; x < x1; ++x) {
        if (row[x] != label) continue;
        part.pixels.emplace_back(x, y);
        part.temperatures_c.push_back(t_row[x]);
      }
    }
    if (static_cast<int>(part.pixels.size()) < options.min_fragment_area_px) continue;
    part.box = cv::boundingRect(part.pixels);
    for (const ColumnSpan& h : heads) {
      part.has_head |= blob.x + h.x0 < x1 && blob.x + h.x1 > x0;
    }
    if (IsObject(part, Median(std::vector<double>(part.temperatures_c.begin(), part.temperatures_c.end())), options))
      continue;
    parts->push_back(std::move(part));
  }
}

// Headless parts join the part with a head above them (in order, so a chain cannot form).
// Returns each part's host (-1: none, it stands for itself).
std::vector<int> JoinHeadlessParts(const PersonDetectorOptions& options, std::vector<Part>* parts) {
  std::vector<int> host(parts->size(), -1);
  for (size_t k = 0; k < parts->size(); ++k) {
    if (!(*parts)[k].has_head) host[k] = HostOf((*parts)[k], *parts, options);
  }
  for (size_t k = 0; k < parts->size(); ++k) {
    if (host[k] < 0) continue;
    Part& into = (*parts)[host[k]];
    const Part& part = (*parts)[k];
    into.box |= part.box;
    into.pixels.insert(into.pixels.end(), part.pixels.begin(), part.pixels.end());
    into.temperatures_c.insert(into.temperatures_c.end(), part.temperatures_c.begin(), part.temperatures_c.end());
  }
  return host;
}

}  // namespace

PersonDetections DetectPersons(const cv::Mat& thermal_u8, const cv::Mat& radiometric_c,
                               const PersonDetectorOptions& options) {
  const std::string problem = options.Check();
  HOILCD_CHECK_MSG(problem.empty(), problem);
  HOILCD_CHECK_MSG(!thermal_u8.empty() || !radiometric_c.empty(), "no image given");
  HOILCD_CHECK(thermal_u8.empty() || thermal_u8.type() == CV_8UC1);
  HOILCD_CHECK(radiometric_c.empty() || radiometric_c.type() == CV_32FC1);
  HOILCD_CHECK(thermal_u8.empty() || radiometric_c.empty() || thermal_u8.size() == radiometric_c.size());

  cv::Mat mask, temperature_c;
  WarmMask(thermal_u8, radiometric_c, options, &mask, &temperature_c);
  cv::Mat labels, stats, centroids;
  const int num_labels = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  std::vector<Part> parts;
  for (int label = 1; label < num_labels; ++label) {
    const cv::Rect blob(stats.at<int>(label, cv::CC_STAT_LEFT), stats.at<int>(label, cv::CC_STAT_TOP),
                        stats.at<int>(label, cv::CC_STAT_WIDTH), stats.at<int>(label, cv::CC_STAT_HEIGHT));
    if (stats.at<int>(label, cv::CC_STAT_AREA) < options.min_fragment_area_px) continue;
    SplitBlob(labels, label, blob, temperature_c, options, &parts);
  }
  const std::vector<int> host = JoinHeadlessParts(options, &parts);

  PersonDetections result;
  result.mask = cv::Mat::zeros(mask.size(), CV_8U);
  for (size_t k = 0; k < parts.size(); ++k) {
    const Part& part = parts[k];
    if (host[k] >= 0) continue;
    if (static_cast<int>(part.pixels.size()) < options.min_area_px) continue;
    if (part.box.height < options.min_height_px) continue;
    const double aspect = static_cast<double>(part.box.height) / part.box.width;
    if (aspect < options.min_aspect_hw || aspect > options.max_aspect_hw) continue;
    const double median_c = Median(std::vector<double>(part.temperatures_c.begin(), part.temperatures_c.end()));
    if (median_c > options.max_median_c) continue;
    if (!radiometric_c.empty() && !LooksHuman(part, options)) continue;
    for (const cv::Point& q : part.pixels) result.mask.at<uint8_t>(q) = 255;
    result.detections.push_back({cv::Rect2f(part.box), static_cast<float>(Score(part, median_c, options))});
  }
  return result;
}

}  // namespace hoilcd
