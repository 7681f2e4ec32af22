// COCO keypoints export of a dataset's ground truth (persons.json): one image per frame, one
// annotation per listed person with its 17 keypoints (COCO visibility flags), box and track id,
// so that pose estimation tools can be evaluated on hoilcd sequences.
#pragma once

#include <string>

#include "hoilcd/core/dataset/dataset.h"

namespace hoilcd {

// The COCO keypoints JSON document of a dataset (images, annotations, categories). Keypoint
// flags: 2 visible, 1 inside the image but occluded, 0 outside the image or behind the camera.
std::string CocoKeypointsJson(const Dataset& dataset);

// Writes OUT_DIR/person_keypoints.json (atomically) for the dataset folder; returns its path.
// Throws InputError for a folder that is not a dataset or whose persons.json has no keypoints.
std::string ExportCoco(const std::string& dataset_dir, const std::string& out_dir);

}  // namespace hoilcd
