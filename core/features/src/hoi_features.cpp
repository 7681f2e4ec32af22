#include "hoilcd/core/features/hoi_features.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "hoilcd/core/util/error.h"

namespace hoilcd {

HoiOptions::HoiOptions() { Table().FillDefaults(this); }

const OptionTable<HoiOptions>& HoiOptions::Table() {
  using O = HoiOptions;
  using R = OptionRange;
  static const OptionTable<O> table = OptionTable<O>()
                                          .Add("min_points_per_person", &O::min_points_per_person, 3, "",
                                               R::Any().AtLeast(0), "a person with fewer bottom points gives none")
                                          .Add("column_step_px", &O::column_step_px, 1, "px", R::Any().AtLeast(1),
                                               "take every n-th column of the track box (1: all, as the paper)");
  return table;
}

std::string HoiOptions::Check() const { return Table().FirstProblem(*this); }

namespace {

// First and one-past-last pixel index whose centre lies in [start, start + length), clipped.
std::pair<int, int> PixelRange(float start, float length, int size) {
  const int first = static_cast<int>(std::ceil(start - 0.5f));
  const int last = static_cast<int>(std::ceil(start + length - 0.5f));
  return {std::clamp(first, 0, size), std::clamp(last, 0, size)};
}

}  // namespace

std::vector<HoiFeature> ExtractHoiFeatures(const cv::Mat& person_mask, const std::vector<Track>& tracks,
                                           const HoiOptions& options) {
  const std::string problem = options.Check();
  HOILCD_CHECK_MSG(problem.empty(), problem);
  HOILCD_CHECK(person_mask.type() == CV_8UC1);
  std::vector<HoiFeature> features;
  for (const Track& track : tracks) {
    const auto [x0, x1] = PixelRange(track.box.x, track.box.width, person_mask.cols);
    const auto [y0, y1] = PixelRange(track.box.y, track.box.height, person_mask.rows);
    const size_t first = features.size();
    for (int x = x0; x < x1; x += options.column_step_px) {
      for (int y = y1 - 1; y >= y0; --y) {
        if (person_mask.at<uint8_t>(y, x) != 0) {
          features.push_back({Point2(static_cast<float>(x), static_cast<float>(y)), track.id});
          break;
        }
      }
    }
    if (features.size() - first < static_cast<size_t>(options.min_points_per_person)) {
      features.resize(first);
    }
  }
  return features;
}

DlcdFrontEnd::DlcdFrontEnd(PersonDetectorOptions detector_options, ByteTrackOptions tracker_options,
                           HoiOptions hoi_options)
    : detector_options_(std::move(detector_options)),
      hoi_options_(std::move(hoi_options)),
      tracker_(std::move(tracker_options)) {
  std::string problem = detector_options_.Check();
  HOILCD_CHECK_MSG(problem.empty(), problem);
  problem = hoi_options_.Check();
  HOILCD_CHECK_MSG(problem.empty(), problem);
}

std::vector<HoiFeature> DlcdFrontEnd::Process(const cv::Mat& thermal_u8, const cv::Mat& radiometric_c) {
  last_detections_ = DetectPersons(thermal_u8, radiometric_c, detector_options_);
  last_tracks_ = tracker_.Update(last_detections_.detections);
  return ExtractHoiFeatures(last_detections_.mask, last_tracks_, hoi_options_);
}

}  // namespace hoilcd
