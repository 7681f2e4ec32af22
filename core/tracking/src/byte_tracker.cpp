#include "hoilcd/core/tracking/byte_tracker.h"

#include <algorithm>
#include <type_traits>
#include <unordered_set>
#include <utility>

#include "hoilcd/core/tracking/box_iou.h"
#include "hoilcd/core/tracking/lapjv.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/sizes.h"

namespace hoilcd {

ByteTrackOptions::ByteTrackOptions() { Table().FillDefaults(this); }

const OptionTable<ByteTrackOptions>& ByteTrackOptions::Table() {
  using O = ByteTrackOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("track_high_thresh", &O::track_high_thresh, 0.5, "", R::Closed(0, 1),
               "detection score above which (strictly) a detection enters the first association")
          .Add("track_low_thresh", &O::track_low_thresh, 0.1, "", R::Closed(0, 1),
               "detection score above which (strictly) a lower one enters the second association")
          .Rule("track_low_thresh",
                [](const O& o) {
                  return o.track_low_thresh <= o.track_high_thresh ? "" : "must be at most track_high_thresh";
                })
          .Add("new_track_thresh", &O::new_track_thresh, 0.6, "", R::Closed(0, 1),
               "a leftover high detection this good starts a track")
          .Add("match_thresh", &O::match_thresh, 0.8, "", R::Any().Above(0).AtMost(1),
               "first association limit on the cost 1 - IoU*score")
          .Add("second_match_thresh", &O::second_match_thresh, 0.5, "", R::Any().Above(0).AtMost(1),
               "low-score association limit on the cost 1 - IoU")
          .Add("unconfirmed_match_thresh", &O::unconfirmed_match_thresh, 0.7, "", R::Any().Above(0).AtMost(1),
               "unconfirmed-track limit on the cost 1 - IoU*score")
          .Add("track_buffer_frames", &O::track_buffer_frames, 30, "frames", R::Closed(0, kMaxFrames),
               "frames at 30 Hz a lost track is kept (scaled by the frame rate)")
          .Add("frame_rate_hz", &O::frame_rate_hz, 25, "Hz", R::Any().Above(0),
               "frame rate; lost tracks live int(rate / 30 * buffer) frames")
          .Add("fuse_score", &O::fuse_score, true,
               "the first association's cost uses IoU * detection score (Python, not MOT20)")
          .AddEnum("iou_convention", &O::iou_convention, IouConvention::kPlusOnePixel,
                   {{"plus_one_pixel", IouConvention::kPlusOnePixel}, {"continuous", IouConvention::kContinuous}},
                   "how IoU measures a box: with 1 px added to width and height (the reference's cython_bbox) "
                   "or continuous");
  return table;
}

std::string ByteTrackOptions::Check() const { return Table().FirstProblem(*this); }

std::vector<std::vector<double>> IouDistance(const std::vector<cv::Rect2f>& a, const std::vector<cv::Rect2f>& b,
                                             IouConvention convention) {
  std::vector<std::vector<double>> cost(a.size(), std::vector<double>(b.size(), 1.0));
  if (convention == IouConvention::kPlusOnePixel) {
    // cython_bbox.bbox_overlaps on (x1, y1, x2, y2) = (x, y, x + w, y + h), in double as there.
    const auto area = [](const cv::Rect2f& r) {
      return (static_cast<double>(r.width) + 1) * (static_cast<double>(r.height) + 1);
    };
    for (size_t i = 0; i < a.size(); ++i) {
      for (size_t j = 0; j < b.size(); ++j) {
        const double iw = std::min(static_cast<double>(a[i].x) + a[i].width, static_cast<double>(b[j].x) + b[j].width) -
                          std::max<double>(a[i].x, b[j].x) + 1;
        if (!(iw > 0)) continue;
        const double ih =
            std::min(static_cast<double>(a[i].y) + a[i].height, static_cast<double>(b[j].y) + b[j].height) -
            std::max<double>(a[i].y, b[j].y) + 1;
        if (!(ih > 0)) continue;
        cost[i][j] = 1.0 - iw * ih / (area(a[i]) + area(b[j]) - iw * ih);
      }
    }
    return cost;
  }
  for (size_t i = 0; i < a.size(); ++i) {
    for (size_t j = 0; j < b.size(); ++j) cost[i][j] = 1.0 - BoxIoU(a[i], b[j]);
  }
  return cost;
}

enum class TrackState { kTracked, kLost, kRemoved };

struct ByteTracker::STrack {
  int id = 0;
  TrackState state = TrackState::kTracked;
  bool activated = false;  // false until a second detection confirms it (except on frame 1)
  KalmanState kf;
  float score = 0;
  int frame_id = 0;     // last frame it was updated (Python's end_frame)
  int start_frame = 0;  // frame it was born
  cv::Rect2f Box() const { return XyahToBox(kf.mean.head<4>()); }
};

ByteTracker::ByteTracker(ByteTrackOptions options) : options_(std::move(options)) {
  const std::string problem = options_.Check();
  HOILCD_CHECK_MSG(problem.empty(), problem);
  max_time_lost_ = static_cast<int>(options_.frame_rate_hz / 30.0 * options_.track_buffer_frames);
}

ByteTracker::~ByteTracker() = default;
ByteTracker::ByteTracker(ByteTracker&&) noexcept = default;
ByteTracker& ByteTracker::operator=(ByteTracker&&) noexcept = default;

namespace {

template <typename T>
std::vector<cv::Rect2f> Boxes(const std::vector<T>& items) {
  std::vector<cv::Rect2f> boxes;
  boxes.reserve(items.size());
  for (const auto& item : items) {
    if constexpr (std::is_same_v<T, Detection>) {
      boxes.push_back(item.box);
    } else {
      boxes.push_back(item->Box());
    }
  }
  return boxes;
}

// matching.fuse_score: cost = 1 - IoU * detection score.
void FuseScore(std::vector<std::vector<double>>& cost, const std::vector<Detection>& detections) {
  for (auto& row : cost) {
    for (size_t j = 0; j < row.size(); ++j) row[j] = 1.0 - (1.0 - row[j]) * detections[j].score;
  }
}

// LinearAssignment, also when there are no tracks (a 0-row matrix cannot say how many
// detections it has).
Assignment Associate(const std::vector<std::vector<double>>& cost, size_t num_detections, double cost_limit) {
  if (!cost.empty()) return LinearAssignment(cost, cost_limit);
  Assignment none;
  for (size_t j = 0; j < num_detections; ++j) none.unmatched_cols.push_back(static_cast<int>(j));
  return none;
}

}  // namespace

void ByteTracker::DropTracks() {
  tracked_.clear();
  lost_.clear();
}

std::vector<Track> ByteTracker::Update(const std::vector<Detection>& detections) {
  ++frame_id_;
  std::vector<Detection> high, low;
  for (const Detection& d : detections) {
    HOILCD_CHECK_MSG(d.box.width > 0 && d.box.height > 0, "empty detection box");
    if (d.score > options_.track_high_thresh) {
      high.push_back(d);
    } else if (d.score > options_.track_low_thresh && d.score < options_.track_high_thresh) {
      low.push_back(d);
    }
  }

  std::vector<TrackPtr> unconfirmed, pool;
  for (const TrackPtr& t : tracked_) (t->activated ? pool : unconfirmed).push_back(t);
  pool.insert(pool.end(), lost_.begin(), lost_.end());
  for (const TrackPtr& t : pool) {
    // A lost track's height velocity is frozen (STrack.multi_predict).
    if (t->state != TrackState::kTracked) t->kf.mean(7) = 0;
    t->kf = kalman_.Predict(t->kf);
  }

  // First association: high-score detections against confirmed and lost tracks.
  std::vector<TrackPtr> refound;
  const IouConvention iou = options_.iou_convention;
  std::vector<std::vector<double>> cost = IouDistance(Boxes(pool), Boxes(high), iou);
  if (options_.fuse_score) FuseScore(cost, high);
  const Assignment first = Associate(cost, high.size(), options_.match_thresh);
  for (const auto& [i, j] : first.matches) {
    if (pool[i]->state != TrackState::kTracked) refound.push_back(pool[i]);
    Refresh(pool[i].get(), high[j]);
  }

  // Second association: low-score detections against the still unmatched tracked tracks.
  std::vector<TrackPtr> remaining;
  for (int i : first.unmatched_rows) {
    if (pool[i]->state == TrackState::kTracked) remaining.push_back(pool[i]);
  }
  const Assignment second =
      Associate(IouDistance(Boxes(remaining), Boxes(low), iou), low.size(), options_.second_match_thresh);
  for (const auto& [i, j] : second.matches) Refresh(remaining[i].get(), low[j]);
  std::vector<TrackPtr> newly_lost;
  for (int i : second.unmatched_rows) {
    remaining[i]->state = TrackState::kLost;
    newly_lost.push_back(remaining[i]);
  }

  // Unconfirmed tracks (seen once) against the high detections left over; unmatched ones die.
  std::vector<Detection> leftover;
  for (int j : first.unmatched_cols) leftover.push_back(high[j]);
  cost = IouDistance(Boxes(unconfirmed), Boxes(leftover), iou);
  if (options_.fuse_score) FuseScore(cost, leftover);
  const Assignment third = Associate(cost, leftover.size(), options_.unconfirmed_match_thresh);
  for (const auto& [i, j] : third.matches) Refresh(unconfirmed[i].get(), leftover[j]);
  for (int i : third.unmatched_rows) unconfirmed[i]->state = TrackState::kRemoved;

  Settle(Birth(leftover, third.unmatched_cols), refound, newly_lost);
  std::vector<Track> output;
  for (const TrackPtr& t : tracked_) {
    if (t->activated) output.push_back({t->id, t->Box(), t->score});
  }
  return output;
}

void ByteTracker::Refresh(STrack* track, const Detection& detection) const {
  track->kf = kalman_.Update(track->kf, BoxToXyah(detection.box));
  track->state = TrackState::kTracked;
  track->activated = true;
  track->frame_id = frame_id_;
  track->score = detection.score;
}

// Confirmed at once only on the first frame.
std::vector<ByteTracker::TrackPtr> ByteTracker::Birth(const std::vector<Detection>& leftovers,
                                                      const std::vector<int>& unmatched) {
  std::vector<TrackPtr> born;
  for (int j : unmatched) {
    if (leftovers[j].score < options_.new_track_thresh) continue;
    auto track = std::make_shared<STrack>();
    track->id = next_id_++;
    track->kf = kalman_.Initiate(BoxToXyah(leftovers[j].box));
    track->activated = frame_id_ == 1;
    track->score = leftovers[j].score;
    track->frame_id = frame_id_;
    track->start_frame = frame_id_;
    born.push_back(std::move(track));
  }
  return born;
}

void ByteTracker::Settle(const std::vector<TrackPtr>& born, const std::vector<TrackPtr>& refound,
                         const std::vector<TrackPtr>& newly_lost) {
  // Lost tracks expire after max_time_lost frames without an update.
  for (const TrackPtr& t : lost_) {
    if (t->state == TrackState::kLost && frame_id_ - t->frame_id > max_time_lost_) {
      t->state = TrackState::kRemoved;
    }
  }
  std::vector<TrackPtr> tracked;
  for (const TrackPtr& t : tracked_) {
    if (t->state == TrackState::kTracked) tracked.push_back(t);
  }
  tracked.insert(tracked.end(), born.begin(), born.end());
  tracked.insert(tracked.end(), refound.begin(), refound.end());
  std::vector<TrackPtr> lost;
  for (const TrackPtr& t : lost_) {
    if (t->state == TrackState::kLost) lost.push_back(t);
  }
  lost.insert(lost.end(), newly_lost.begin(), newly_lost.end());

  // Duplicates (a tracked and a lost track on the same box): keep the one tracked longer.
  const std::vector<std::vector<double>> overlap = IouDistance(Boxes(tracked), Boxes(lost), options_.iou_convention);
  std::unordered_set<size_t> drop_tracked, drop_lost;
  for (size_t p = 0; p < tracked.size(); ++p) {
    for (size_t q = 0; q < lost.size(); ++q) {
      if (overlap[p][q] >= 0.15) continue;
      const int age_p = tracked[p]->frame_id - tracked[p]->start_frame;
      const int age_q = lost[q]->frame_id - lost[q]->start_frame;
      if (age_p > age_q) {
        drop_lost.insert(q);
      } else {
        drop_tracked.insert(p);
      }
    }
  }
  tracked_.clear();
  lost_.clear();
  for (size_t p = 0; p < tracked.size(); ++p) {
    if (!drop_tracked.count(p)) tracked_.push_back(tracked[p]);
  }
  for (size_t q = 0; q < lost.size(); ++q) {
    if (!drop_lost.count(q)) lost_.push_back(lost[q]);
  }
}

}  // namespace hoilcd
