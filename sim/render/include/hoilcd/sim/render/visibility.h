// Ground truth about people in a rendered frame (persons.json): COCO keypoints, visible box, visible pixel
// fraction against the person rendered alone, occlusion fraction, the projected 3-D
// human–object contact points of the asset (seat, table, floor) with their visibility, and
// image-space contacts ("table_edge", "chair_edge": where the bottom of the visible person meets
// a table or chair in the image, the ground truth for DLCD's HOI points).
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/geometry/camera.h"
#include "hoilcd/sim/world/world.h"

namespace hoilcd {

// instance_ids: CV_32S per-pixel World instance labels of the frame; depth_m: CV_32F depth
// along the camera's z axis (FrameBuffers::depth_m; empty: no keypoint is marked visible). Lists
// every person present and in view, in person-id order: with their visible-pixel box, or, when
// something hides them completely, with visible fraction 0 and the box they would cover alone;
// with their contacts and 17 COCO keypoints projected. People are looked at on `threads`
// threads (0: every core); the result does not depend on it.
std::vector<PersonRecord> VisiblePersons(const World& world, const CameraIntrinsics& intrinsics, const CameraPose& pose,
                                         const cv::Mat& instance_ids, const cv::Mat& depth_m, int threads = 1);

}  // namespace hoilcd
