// The front ends loop-closure methods share: per-frame extraction run once for every method that
// needs it, in one pass that reads and decodes each frame once. Keypoints, thumbnails and person
// detection are per frame (in parallel, identical at any thread count); ByteTrack then runs in
// frame order (the tracker carries state), block by block, and the HOI points per frame. Two
// oracle front ends read the dataset's ground truth in place of the camera or the detector.
#pragma once

#include <set>
#include <string>
#include <vector>

#include "hoilcd/bench/evaluation/tracking_metrics.h"
#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/features/hoi_features.h"
#include "hoilcd/core/features/keypoints.h"
#include "hoilcd/core/features/person_detection.h"
#include "hoilcd/core/place_recognition/retrieval_index.h"
#include "hoilcd/core/place_recognition/thumbnail_baseline.h"
#include "hoilcd/core/tracking/byte_tracker.h"

namespace hoilcd {

enum class FrontEnd {
  kKeypoints,   // SLCD's corner keypoints of the 8-bit frame
  kPersons,     // DLCD's person detection, tracking and HOI points
  kThumbnails,  // patch-normalised thumbnails (SeqSLAM-style)
  // Oracles (diagnostics), from the dataset's ground truth:
  kIdealKeypoints,  // kKeypoints' corners of the noise-free true temperature (EXR T_true) in the 8-bit window
  kTruePersons,     // kPersons' HOI points from the true people (EXR class mask, persons.json boxes and ids)
};

// The dataset outputs (DatasetOutputs names) a front end reads besides the thermal frames.
std::vector<std::string> GroundTruthOutputs(FrontEnd front_end);

struct FrontEndOptions {
  KeypointOptions keypoints;
  PersonDetectorOptions detector;
  ByteTrackOptions tracker;
  HoiOptions hoi;
  ThumbnailOptions thumbnail;
  int threads = 0;  // 0 = every core
};

// What the front ends computed; only the parts of the front ends that ran are filled.
struct FrontEndOutput {
  std::set<FrontEnd> ran;
  std::vector<std::vector<Point2>> keypoints;  // per frame
  RetrievalIndex keypoint_index;               // keypoints, frame by frame
  std::vector<double> keypoints_ms;            // per frame extraction time, ms
  std::vector<std::vector<HoiFeature>> hoi;    // per frame
  RetrievalIndex hoi_index;                    // HOI points, frame by frame
  std::vector<FrameTracks> tracks;             // per frame: the tracker's boxes and their HOI points
  std::vector<double> persons_ms;
  ThumbnailIndex thumbnails;
  std::vector<double> thumbnails_ms;
  std::vector<std::vector<Point2>> ideal_keypoints;  // per frame (kIdealKeypoints)
  RetrievalIndex ideal_keypoint_index;
  std::vector<double> ideal_keypoints_ms;
  std::vector<std::vector<HoiFeature>> true_hoi;  // per frame (kTruePersons), track_id = person id
  RetrievalIndex true_hoi_index;
  std::vector<double> true_persons_ms;
  bool Ran(FrontEnd f) const { return ran.count(f) > 0; }
};

FrontEndOutput RunFrontEnds(const Dataset& dataset, const std::set<FrontEnd>& needed, const FrontEndOptions& options);

}  // namespace hoilcd
