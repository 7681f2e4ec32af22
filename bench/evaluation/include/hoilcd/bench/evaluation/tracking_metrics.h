// Person tracking quality against the persons.json ground truth: detection precision and recall
// at an IoU threshold, CLEAR MOT (MOTA, id switches), IDF1 (one global track-to-person id
// assignment), and how close the predicted HOI points come to the ground-truth contact points.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/tracking/box_iou.h"
#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

struct TrackedBox {
  int id = -1;                             // track id
  cv::Rect2f box;                          // px
  std::vector<cv::Point2f> hoi_points_px;  // HOI feature points of this track, may be empty
};

struct FrameTracks {
  int frame = 0;
  std::vector<TrackedBox> tracks;
};

// Defaults and ranges: Table() in tracking_metrics.cpp.
struct TrackingMetricsOptions {
  double iou_threshold;         // IoU (0..1) a prediction needs with a person to match it
  double min_visible_fraction;  // 0..1; less visible persons are ignored: never missed, and a
                                // prediction on one is not a false positive
  double min_box_height_px;     // px; persons whose visible box is lower are ignored likewise
                                // (slivers at the image edge or between others)
  double hoi_tolerance_px;      // px, a contact this close to its nearest HOI point is a hit

  TrackingMetricsOptions();  // the registered defaults
  // Every field once: name, default, unit, range, description.
  static const OptionTable<TrackingMetricsOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

struct TrackingMetrics {
  int frames = 0;
  int gt_boxes = 0;         // ground-truth person boxes (ignored ones left out)
  int predicted_boxes = 0;  // predicted boxes (those on ignored persons left out)
  int true_positives = 0;   // CLEAR MOT matches
  int false_positives = 0;
  int false_negatives = 0;
  int id_switches = 0;     // a person matched to a different track than its last match
  double precision = NAN;  // TP / (TP + FP)
  double recall = NAN;     // TP / (TP + FN)
  double mota = NAN;       // 1 - (FN + FP + IDSW) / GT
  int idtp = 0, idfp = 0, idfn = 0;
  double idf1 = NAN;  // 2 IDTP / (GT + predicted)
  // HOI points: for each visible GT contact of a matched person, the distance to the nearest HOI
  // point of the matched track.
  int hoi_contacts = 0;                        // visible contacts of matched persons
  int hoi_contacts_without_points = 0;         // of those, whose track had no HOI point (count as misses)
  double hoi_median_error_px = NAN;            // over contacts whose track had HOI points
  double hoi_fraction_within_tolerance = NAN;  // over all hoi_contacts

  nlohmann::json ToJson() const;  // NaN becomes null
};

// Frames are matched by number; a frame absent from one side has no boxes on that side.
TrackingMetrics ComputeTrackingMetrics(const std::vector<FramePersons>& ground_truth,
                                       const std::vector<FrameTracks>& predicted,
                                       const TrackingMetricsOptions& options = {});

}  // namespace hoilcd
