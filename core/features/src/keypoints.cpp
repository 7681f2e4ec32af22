#include "hoilcd/core/features/keypoints.h"

#include <algorithm>

#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/sizes.h"

namespace hoilcd {

namespace {

// More than a thermal frame has pixels (256 x 192 = 49,152) and a hundred times the paper's
// SuperPoint budget; ORB is asked for twice this, which must fit an int.
constexpr int kMaxKeypoints = 100000;

}  // namespace

KeypointOptions::KeypointOptions() { Table().FillDefaults(this); }

const OptionTable<KeypointOptions>& KeypointOptions::Table() {
  using O = KeypointOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("detector", &O::detector, "gftt", {"gftt", "fast", "orb", "sift", "akaze"}, "keypoint detector")
          .Add("max_keypoints", &O::max_keypoints, 1000, "", R::Closed(1, kMaxKeypoints),
               "keypoints kept per frame, strongest first")
          .Add("nms_radius_px", &O::nms_radius_px, 4.0, "px", R::Any().AtLeast(0),
               "minimum distance between keypoints (SuperPoint's NMS: 4)")
          .Add("border_px", &O::border_px, 4, "px", R::Closed(0, kMaxImageSidePx),
               "keypoints this close to the image border are ignored")
          .Add("gftt_quality", &O::gftt_quality, 0.01, "", R::Any().Above(0).Below(1),
               "GFTT quality level, fraction of the strongest corner")
          .Add("gftt_block_size_px", &O::gftt_block_size_px, 3, "px", R::Closed(3, kMaxImageSidePx),
               "GFTT structure-tensor window")
          .Add("gftt_min_eigenvalue", &O::gftt_min_eigenvalue, 5e-4, "", R::Any().AtLeast(0),
               "absolute floor on the Shi-Tomasi score")
          .Add("fast_threshold", &O::fast_threshold, 10, "", R::Closed(1, 255),
               "FAST intensity threshold, 8-bit levels")
          .Add("blur_sigma_px", &O::blur_sigma_px, 0.0, "px", R::Any().AtLeast(0), "Gaussian pre-blur (0: none)");
  return table;
}

std::string KeypointOptions::Check() const { return Table().FirstProblem(*this); }

std::vector<Point2> DetectKeypoints(const cv::Mat& thermal_u8, const KeypointOptions& options) {
  HOILCD_CHECK_MSG(options.Check().empty(), options.Check());
  HOILCD_CHECK(thermal_u8.type() == CV_8U && !thermal_u8.empty());
  cv::Mat image = thermal_u8;
  if (options.blur_sigma_px > 0) cv::GaussianBlur(thermal_u8, image, cv::Size(), options.blur_sigma_px);
  cv::Mat mask(image.size(), CV_8U, cv::Scalar(0));
  const int b = options.border_px;
  if (image.cols > 2 * b && image.rows > 2 * b) {
    mask(cv::Rect(b, b, image.cols - 2 * b, image.rows - 2 * b)).setTo(255);
  }
  std::vector<Point2> out;
  if (options.detector == "gftt") {
    if (options.gftt_min_eigenvalue > 0) {
      cv::Mat strength;
      cv::cornerMinEigenVal(image, strength, options.gftt_block_size_px, 3);
      mask &= (strength >= options.gftt_min_eigenvalue);
    }
    std::vector<cv::Point2f> corners;
    cv::goodFeaturesToTrack(image, corners, options.max_keypoints, options.gftt_quality,
                            std::max(1.0, options.nms_radius_px), mask, options.gftt_block_size_px);
    return corners;
  }
  std::vector<cv::KeyPoint> keypoints;
  if (options.detector == "fast") {
    cv::FAST(image, keypoints, options.fast_threshold, /*nonmaxSuppression=*/true);
  } else if (options.detector == "orb") {
    cv::ORB::create(options.max_keypoints * 2)->detect(image, keypoints, mask);
  } else if (options.detector == "sift") {
    cv::SIFT::create()->detect(image, keypoints, mask);
  } else {
    cv::AKAZE::create()->detect(image, keypoints, mask);
  }
  // Strongest first (ties by position, so the order never depends on the detector's internals),
  // then the border and a greedy radius suppression like SuperPoint's NMS.
  std::sort(keypoints.begin(), keypoints.end(), [](const cv::KeyPoint& a, const cv::KeyPoint& c) {
    if (a.response != c.response) return a.response > c.response;
    if (a.pt.y != c.pt.y) return a.pt.y < c.pt.y;
    return a.pt.x < c.pt.x;
  });
  const float r2 = static_cast<float>(options.nms_radius_px * options.nms_radius_px);
  for (const cv::KeyPoint& k : keypoints) {
    if (static_cast<int>(out.size()) >= options.max_keypoints) break;
    if (k.pt.x < b || k.pt.y < b || k.pt.x >= image.cols - b || k.pt.y >= image.rows - b) continue;
    const bool close = std::any_of(out.begin(), out.end(), [&](const Point2& p) {
      const float dx = p.x - k.pt.x, dy = p.y - k.pt.y;
      return dx * dx + dy * dy < r2;
    });
    if (!close) out.push_back(k.pt);
  }
  return out;
}

}  // namespace hoilcd
