// Human-object interaction (HOI) feature points, paper section 4.2.1: per tracked person and per
// image column of the track box, the bottom-most pixel of (track box AND person mask), where a
// person meets the chair, table or floor. DlcdFrontEnd runs detection -> ByteTrack -> HOI
// extraction frame by frame.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "hoilcd/core/features/person_detection.h"
#include "hoilcd/core/geometry/point.h"
#include "hoilcd/core/tracking/byte_tracker.h"
#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

struct HoiFeature {
  Point2 point;      // px, integer pixel indices (column, row) of the bottom-most person pixel
  int track_id = 0;  // ByteTrack id of the person
};

// Defaults and ranges: Table() in hoi_features.cpp.
struct HoiOptions {
  int min_points_per_person;  // points; a person with fewer bottom points gives none
  int column_step_px;         // px, take every n-th column of the box (1 = all, as the paper)

  HoiOptions();  // the registered defaults
  // Every field once: name, default, unit, range, description.
  static const OptionTable<HoiOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

// `person_mask`: CV_8UC1, non-zero = person pixel. A column belongs to a box when its pixel
// centre x + 0.5 lies in [box.x, box.x + box.width); rows likewise; boxes are clipped to the
// image. Points come track by track (input order), columns left to right.
std::vector<HoiFeature> ExtractHoiFeatures(const cv::Mat& person_mask, const std::vector<Track>& tracks,
                                           const HoiOptions& options);

// The whole DLCD front end over a sequence; the tracker state is carried between frames.
class DlcdFrontEnd {
 public:
  DlcdFrontEnd(PersonDetectorOptions detector_options, ByteTrackOptions tracker_options, HoiOptions hoi_options);

  // One frame in (see DetectPersons for the images), its HOI feature points out.
  std::vector<HoiFeature> Process(const cv::Mat& thermal_u8, const cv::Mat& radiometric_c);

  const PersonDetections& last_detections() const { return last_detections_; }
  const std::vector<Track>& last_tracks() const { return last_tracks_; }

 private:
  PersonDetectorOptions detector_options_;
  HoiOptions hoi_options_;
  ByteTracker tracker_;
  PersonDetections last_detections_;
  std::vector<Track> last_tracks_;
};

}  // namespace hoilcd
