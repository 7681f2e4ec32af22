// One side of `hoilcd realism` grouped by native frame size (W x H): the only camera identity a
// .npy or PNG carries. The spectrum slope's top octave and the flat-region noise are the camera's
// signature, so the report gives them per size rather than mixed over cameras.
#pragma once

#include <cmath>
#include <vector>

#include <nlohmann/json.hpp>

#include "hoilcd/bench/realism/frame_statistics.h"

namespace hoilcd {

struct FrameSizeGroup {
  int width_px = 0, height_px = 0;  // native frame size
  int views = 0;                    // frames of this size
  int not_blank = 0;                // of them, not blank
  // Medians over the views that are not blank (NaN values left out; NaN when none has one).
  double spectrum_slope = NAN;
  double flat_noise_k = NAN;
  double flat_noise_lag1 = NAN;
};

// Groups by (width_px, height_px), the most frames first, then by width and height.
std::vector<FrameSizeGroup> GroupByFrameSize(const std::vector<FrameStatistics>& statistics);

// A JSON array, one object per group (missing medians as null).
nlohmann::json FrameSizeGroupsJson(const std::vector<FrameSizeGroup>& groups);

}  // namespace hoilcd
