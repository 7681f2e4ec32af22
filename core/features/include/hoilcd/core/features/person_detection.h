// Person detection in thermal frames for the dynamic-landmark loop closure (DLCD): threshold at
// clothing temperature, clean up, split blobs where seated neighbours touch, reject warm objects
// by shape and temperature, and score each person in (0, 1] for ByteTrack.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "hoilcd/core/tracking/byte_tracker.h"
#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

// Defaults and ranges: Table() in person_detection.cpp.
struct PersonDetectorOptions {
  // Thresholding and clean-up.
  double threshold_c;   // degC (people's clothing is 27-30); on an 8-bit frame alone, the
                        // first level at or above it in the window below
  double u8_min_c;      // degC shown as 0 in the 8-bit frame (the manifest's window_min_c)
  double u8_max_c;      // degC shown as 255 in the 8-bit frame (the manifest's window_max_c)
  int open_kernel_px;   // px, elliptic opening diameter that removes speckle (0 = none)
  int close_kernel_px;  // px, elliptic closing diameter that fills small holes (0 = none)
  // Splitting touching neighbours (column-projection valleys between heads).
  int profile_smooth_px;          // px, box-filter width over the per-column pixel counts
  double split_valley_ratio;      // split at a valley at most this fraction of the lower peak
  double valley_tolerance_ratio;  // of the lower peak; valley floor cut in its middle
  double min_peak_ratio;          // a peak is a person only if >= this fraction of the blob's max
  int min_split_width_px;         // px, every part of a split is at least this wide
  // Head seeds (radiometric frames only: the 8-bit frame saturates below skin temperature). A
  // blob with two or more heads is split between them; with one it is not split at all.
  double head_min_c;       // degC, skin (32-35) is hotter, hair and clothing are cooler
  int min_head_area_px;    // px^2, smaller skin spots are ignored
  double head_zone_ratio;  // a head's top lies in this upper fraction of its blob
  // Parts without a head below a part with one (legs under a table, a forearm cut off by an
  // occluder) join it when they overlap its columns.
  double merge_min_overlap;  // of the headless part's width, column overlap to join
  int min_fragment_area_px;  // px^2, smaller parts are dropped before merging
  // Rejection of non-people (each part after splitting).
  int min_area_px;          // px^2, smaller (merged) parts are noise or cups
  int min_height_px;        // px, lower parts are ignored
  double min_aspect_hw;     // height/width, flatter parts are laptops, radiators, tables
  double max_aspect_hw;     // height/width, taller parts are pipes or door frames
  double max_median_c;      // degC, hotter parts are cups (> 40) or radiators (~40)
  double hot_c;             // degC; the 8-bit image saturates here (u8_max_c)
  double max_hot_fraction;  // parts with more pixels >= hot_c are laptops, cups, radiators
  double max_fill_ratio;    // area / box area; rectangles fill more ...
  double max_solidity;      // ... and are convex (area / hull area): both => object
  // Fraction of a part's columns whose top pixel lies within 1 px of the median top row: screens
  // and monitors have straight top edges (0.8-1.0 on rendered paper-room frames), people round
  // heads and shoulders (95 % below 0.62). Parts touching the image top are exempt.
  double max_flat_top_fraction;
  // Radiometric frames only (the 8-bit frame saturates below skin temperature). A person shows
  // skin (face, neck, ears: head_min_c to max_median_c) in the top zone of its box or, seen from
  // behind with the head hidden by the shoulders, is mostly clothing. Warm objects are neither: on
  // rendered paper-room frames upper clothing reads 27.3-28.8 degC, laptop lids 29.1-29.6, monitor
  // screens 26.6-26.8, and a laptop base's 31 lies at its bottom. Trousers read 26.6-27.1, so legs
  // seen alone under a table are dropped too (under a detected person they join it). Parts
  // touching the image top are exempt (the head may be cut off).
  int min_top_skin_px;           // px^2, skin pixels needed in the top zone (0 = rule off)
  double top_skin_zone_ratio;    // upper fraction of the part's box height: the top zone
  double clothing_min_c;         // degC, lowest apparent temperature counted as clothing
  double clothing_max_c;         // degC, highest apparent temperature counted as clothing
  double min_clothing_fraction;  // of a part's pixels at clothing temperature, when no skin
  // Score = geometric mean of an area, a shape and a temperature score.
  double score_area_px;        // px^2, area at which the area score is 1 - 1/e
  double typical_aspect_hw;    // height/width of a seated person, shape score 1
  double aspect_sigma_log;     // natural-log units, width of the shape score
  double person_min_c;         // degC, median below this lowers the temperature score
  double person_max_c;         // degC, median above this lowers the temperature score
  double temperature_sigma_c;  // degC, fall-off of the temperature score outside the range

  PersonDetectorOptions();  // the registered defaults
  // Every field once: name, default, unit, range, description.
  static const OptionTable<PersonDetectorOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

struct PersonDetections {
  std::vector<Detection> detections;
  cv::Mat mask;  // CV_8U 0/255: pixels of the accepted people after clean-up
};

// `thermal_u8`: CV_8UC1 display image (may be empty when `radiometric_c` is given);
// `radiometric_c`: CV_32FC1 apparent temperature in degC, or empty. Same size when both given.
// Detections come in reading order of their blobs (then left to right within a split blob).
PersonDetections DetectPersons(const cv::Mat& thermal_u8, const cv::Mat& radiometric_c,
                               const PersonDetectorOptions& options);

// Where a blob with these per-column pixel counts splits: ascending columns (0-based within the
// profile) at which a new part starts. Exposed for tests.
std::vector<int> FindSplitColumns(const std::vector<double>& column_counts, const PersonDetectorOptions& options);

}  // namespace hoilcd
