// SLCD's keypoints: 2-D corner coordinates of a thermal image (only coordinates are used, as in
// the paper). The paper's SuperPoint cannot be shipped (weights and licence), so the default is
// Shi–Tomasi (GFTT) with SuperPoint-like settings; FAST, ORB, SIFT and AKAZE are selectable.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "hoilcd/core/geometry/point.h"

namespace hoilcd {

struct KeypointOptions {
  std::string detector = "gftt";     // gftt | fast | orb | sift | akaze
  int max_keypoints = 1000;          // keep at most this many, strongest first
  double nms_radius_px = 4.0;        // minimum distance between keypoints, px (SuperPoint NMS 4)
  int border_px = 4;                 // ignore keypoints this close to the image border, px
  double gftt_quality = 0.01;        // GFTT quality level, fraction of the strongest corner (below ~0.005 it fires on sensor noise)
  int gftt_block_size_px = 3;        // GFTT structure-tensor window, px
  // Absolute floor on the Shi–Tomasi score (min eigenvalue of the structure tensor of the 8-bit
  // image scaled to [0, 1], OpenCV's cornerMinEigenVal), like SuperPoint's detection threshold:
  // GFTT's quality level is relative, so on a uniform wall it picks sensor noise and the fixed
  // pattern, which is the same in every frame and "matches" everywhere. Noise peaks at ~1.5e-4
  // on paper_room frames; real corners reach 1e-3 to 1e-1.
  double gftt_min_eigenvalue = 5e-4;
  int fast_threshold = 10;           // FAST intensity threshold, 8-bit levels
  double blur_sigma_px = 0.0;        // Gaussian pre-blur, px (0: none)
  std::string Check() const;
};

// Keypoint coordinates of an 8-bit thermal image, strongest first; deterministic.
std::vector<Point2> DetectKeypoints(const cv::Mat& thermal_u8, const KeypointOptions& options);

}  // namespace hoilcd
