// SLCD's keypoints: 2-D corner coordinates of a thermal image (only coordinates are used, as in
// the paper). The paper's SuperPoint cannot be shipped (weights and licence), so the default is
// Shi–Tomasi (GFTT) with SuperPoint-like settings; FAST, ORB, SIFT and AKAZE are selectable.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "hoilcd/core/geometry/point.h"
#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

// Defaults and ranges: Table() in keypoints.cpp.
struct KeypointOptions {
  std::string detector;  // gftt | fast | orb | sift | akaze
  int max_keypoints;     // keep at most this many, strongest first
  double nms_radius_px;  // minimum distance between keypoints, px (SuperPoint NMS 4)
  int border_px;         // ignore keypoints this close to the image border, px
  double gftt_quality;   // GFTT quality level, fraction of the strongest corner (below ~0.005 it fires on sensor noise)
  int gftt_block_size_px;  // GFTT structure-tensor window, px
  // Absolute floor on the Shi–Tomasi score (min eigenvalue of the structure tensor of the 8-bit
  // image scaled to [0, 1], OpenCV's cornerMinEigenVal), like SuperPoint's detection threshold:
  // GFTT's quality level is relative, so on a uniform wall it picks sensor noise and the fixed
  // pattern, which is the same in every frame and "matches" everywhere. Noise peaks at ~1.5e-4
  // on paper_room frames; real corners reach 1e-3 to 1e-1.
  double gftt_min_eigenvalue;
  int fast_threshold;    // FAST intensity threshold, 8-bit levels
  double blur_sigma_px;  // Gaussian pre-blur, px (0: none)

  KeypointOptions();  // the registered defaults
  // Every field once: name, default, unit, range, description.
  static const OptionTable<KeypointOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

// Keypoint coordinates of an 8-bit thermal image, strongest first; deterministic.
std::vector<Point2> DetectKeypoints(const cv::Mat& thermal_u8, const KeypointOptions& options);

}  // namespace hoilcd
