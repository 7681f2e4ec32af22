// ByteTrack (Zhang et al., ECCV 2022): multi-object tracking by associating every detection box,
// high and low score, to Kalman-predicted tracks by IoU. Follows BYTETracker.update of the Python
// reference (ifzhang/ByteTrack, yolox/tracker/byte_tracker.py).
//
// The official C++ ports (deploy/TensorRT, ncnn) differ from the Python reference: they skip the
// score fusion of the IoU cost and the 0.1 floor under low-score detections. We follow Python.
// IoU follows the reference's cython_bbox by default (1 px added to widths and heights); the
// continuous convention is an option. Known, deliberate differences from Python: a lost track
// that expires is dropped at once (Python keeps it in the lost pool for one more frame because
// it subtracts the removed list before extending it); track ids count from 1 per tracker instead
// of per process. tests/core/byte_tracker_reference_test.cpp replays detections through both.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <opencv2/core/types.hpp>

#include "hoilcd/core/tracking/kalman_filter.h"
#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

struct Detection {
  cv::Rect2f box;   // px (x, y, w, h), top-left origin
  float score = 0;  // detector confidence in (0, 1]
};

// How IoU measures a box (x, y, w, h): as the continuous rectangle, or as cython_bbox.bbox_overlaps
// does for the reference, inclusive pixel corners, i.e. w + 1 by h + 1.
enum class IouConvention { kPlusOnePixel, kContinuous };

// Defaults and ranges: Table() in byte_tracker.cpp.
struct ByteTrackOptions {
  double track_high_thresh;         // score; above (strictly, as Python): first association
  double track_low_thresh;          // score; strictly between low and high: second association
  double new_track_thresh;          // score; a leftover high detection this good starts a track
  double match_thresh;              // cost 1 - IoU*score; first association limit
  double second_match_thresh;       // cost 1 - IoU; low-score association limit
  double unconfirmed_match_thresh;  // cost 1 - IoU*score; unconfirmed-track limit
  int track_buffer_frames;          // frames at 30 Hz a lost track is kept (scaled by the rate)
  double frame_rate_hz;             // Hz; lost tracks live int(rate / 30 * buffer) frames
  bool fuse_score;                  // cost uses IoU * detection score (Python, not MOT20)
  IouConvention iou_convention;     // the reference's (cython_bbox)

  ByteTrackOptions();  // the registered defaults
  // Every field once: name, default, unit, range, description.
  static const OptionTable<ByteTrackOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

struct Track {
  int id = 0;       // from 1, never reused by one tracker
  cv::Rect2f box;   // px, the Kalman-filtered box
  float score = 0;  // score of the detection that last updated the track
};

// 1 - IoU for every (a, b) pair: rows = a, cols = b.
std::vector<std::vector<double>> IouDistance(const std::vector<cv::Rect2f>& a, const std::vector<cv::Rect2f>& b,
                                             IouConvention convention = IouConvention::kContinuous);

class ByteTracker {
 public:
  explicit ByteTracker(ByteTrackOptions options = {});
  ~ByteTracker();
  ByteTracker(ByteTracker&&) noexcept;
  ByteTracker& operator=(ByteTracker&&) noexcept;

  // One frame of detections in; the activated tracks of this frame out (BYTETracker.update's
  // output_stracks). Detections scoring at most track_low_thresh are ignored.
  std::vector<Track> Update(const std::vector<Detection>& detections);

  // Forgets every track, tracked and lost (a new recording: nothing in view carries over); ids count
  // on, so none is given twice.
  void DropTracks();

  int frame_count() const { return frame_id_; }
  // How many frames a track may stay lost before it is removed.
  int max_time_lost_frames() const { return max_time_lost_; }

 private:
  struct STrack;
  using TrackPtr = std::shared_ptr<STrack>;

  // A matched detection's update of a track: Kalman update, tracked and confirmed, its score.
  void Refresh(STrack* track, const Detection& detection) const;
  // New tracks from leftovers[j] (j in `unmatched`) scoring at least new_track_thresh.
  std::vector<TrackPtr> Birth(const std::vector<Detection>& leftovers, const std::vector<int>& unmatched);
  // The frame's bookkeeping after the associations: lost tracks expire, the tracked and lost
  // lists are rebuilt with the born, refound and newly lost tracks, duplicates are removed.
  void Settle(const std::vector<TrackPtr>& born, const std::vector<TrackPtr>& refound,
              const std::vector<TrackPtr>& newly_lost);

  ByteTrackOptions options_;
  KalmanFilterXYAH kalman_;
  int max_time_lost_ = 0;
  int frame_id_ = 0;
  int next_id_ = 1;
  std::vector<TrackPtr> tracked_;  // state Tracked (confirmed or not), in Python's order
  std::vector<TrackPtr> lost_;     // state Lost
};

}  // namespace hoilcd
