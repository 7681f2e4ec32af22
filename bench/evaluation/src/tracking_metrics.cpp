#include "hoilcd/bench/evaluation/tracking_metrics.h"

#include <algorithm>
#include <map>
#include <set>

#include "hoilcd/bench/evaluation/json_number.h"
#include "hoilcd/core/tracking/lapjv.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/stats.h"

namespace hoilcd {
namespace {

// Assignment costs: 1 - IoU for pairs at or above the threshold (at most 1 - threshold), a value
// above the limit for the rest, so LinearAssignment never matches them and prefers more matches.
constexpr double kCostLimit = 1.0;
constexpr double kForbiddenCost = 2.0;

// Matches persons (rows) to predicted boxes (columns) with IoU >= threshold: as many as
// possible, then the largest total IoU.
std::vector<std::pair<int, int>> MatchByIoU(const std::vector<cv::Rect2f>& persons,
                                            const std::vector<cv::Rect2f>& boxes, double iou_threshold) {
  if (persons.empty() || boxes.empty()) return {};
  std::vector<std::vector<double>> cost(persons.size(), std::vector<double>(boxes.size()));
  for (size_t i = 0; i < persons.size(); ++i) {
    for (size_t j = 0; j < boxes.size(); ++j) {
      const double iou = BoxIoU(persons[i], boxes[j]);
      cost[i][j] = iou >= iou_threshold ? 1.0 - iou : kForbiddenCost;
    }
  }
  std::vector<std::pair<int, int>> matches;
  for (const auto& [i, j] : LinearAssignment(cost, kCostLimit).matches) {
    if (cost[i][j] < kCostLimit) matches.emplace_back(i, j);
  }
  return matches;
}

std::vector<cv::Rect2f> PersonBoxes(const std::vector<const PersonRecord*>& persons) {
  std::vector<cv::Rect2f> out;
  for (const PersonRecord* p : persons) out.push_back(p->box_px);
  return out;
}

std::vector<cv::Rect2f> TrackBoxes(const std::vector<const TrackedBox*>& tracks) {
  std::vector<cv::Rect2f> out;
  for (const TrackedBox* t : tracks) out.push_back(t->box);
  return out;
}

// One frame's persons and tracks, as evaluated.
struct FrameBoxes {
  std::vector<const PersonRecord*> persons;
  std::vector<const TrackedBox*> tracks;
};

// Each frame's persons and tracks, by frame number (a frame absent from one side has none there).
std::map<int, FrameBoxes> FramesOf(const std::vector<FramePersons>& ground_truth,
                                   const std::vector<FrameTracks>& predicted) {
  std::map<int, FrameBoxes> frames;
  std::set<int> truth_frames, track_frames;
  for (const FramePersons& f : ground_truth) {
    HOILCD_CHECK_MSG(truth_frames.insert(f.frame).second, "frame " << f.frame << " twice");
    for (const PersonRecord& p : f.persons) frames[f.frame].persons.push_back(&p);
    frames[f.frame];
  }
  for (const FrameTracks& f : predicted) {
    HOILCD_CHECK_MSG(track_frames.insert(f.frame).second, "frame " << f.frame << " twice");
    std::set<int> ids;
    FrameBoxes& boxes = frames[f.frame];
    for (const TrackedBox& t : f.tracks) {
      HOILCD_CHECK_MSG(ids.insert(t.id).second, "track " << t.id << " twice in frame " << f.frame);
      boxes.tracks.push_back(&t);
    }
  }
  return frames;
}

// Leaves out the persons too hidden or too low to score, and the predictions matching them.
void DropIgnored(const TrackingMetricsOptions& options, FrameBoxes* frame) {
  const auto is_ignored = [&](const PersonRecord* p) {
    return p->visible_fraction < options.min_visible_fraction || p->box_px.height < options.min_box_height_px;
  };
  std::vector<const PersonRecord*>& persons = frame->persons;
  if (std::none_of(persons.begin(), persons.end(), is_ignored)) return;
  std::vector<uint8_t> drop_track(frame->tracks.size(), 0);
  for (const auto& [i, j] : MatchByIoU(PersonBoxes(persons), TrackBoxes(frame->tracks), options.iou_threshold)) {
    if (is_ignored(persons[i])) drop_track[j] = 1;
  }
  std::vector<const TrackedBox*> kept;
  for (size_t j = 0; j < frame->tracks.size(); ++j) {
    if (!drop_track[j]) kept.push_back(frame->tracks[j]);
  }
  frame->tracks = std::move(kept);
  persons.erase(std::remove_if(persons.begin(), persons.end(), is_ignored), persons.end());
}

// CLEAR MOT's matches of one frame (person index, track index): last frame's correspondences
// (person id -> track id) that are still valid, then an IoU assignment of the rest.
std::vector<std::pair<int, int>> ClearMotMatches(const FrameBoxes& frame,
                                                 const std::map<int, int>& previous_frame_match, double iou_threshold) {
  const std::vector<const PersonRecord*>& persons = frame.persons;
  const std::vector<const TrackedBox*>& tracks = frame.tracks;
  std::vector<std::pair<int, int>> matches;
  std::vector<uint8_t> person_used(persons.size(), 0), track_used(tracks.size(), 0);
  for (size_t i = 0; i < persons.size(); ++i) {
    const auto previous = previous_frame_match.find(persons[i]->id);
    if (previous == previous_frame_match.end()) continue;
    for (size_t j = 0; j < tracks.size(); ++j) {
      if (tracks[j]->id == previous->second && !track_used[j] &&
          BoxIoU(persons[i]->box_px, tracks[j]->box) >= iou_threshold) {
        matches.emplace_back(i, j);
        person_used[i] = track_used[j] = 1;
        break;
      }
    }
  }
  std::vector<int> free_persons, free_tracks;
  std::vector<cv::Rect2f> free_person_boxes, free_track_boxes;
  for (size_t i = 0; i < persons.size(); ++i) {
    if (person_used[i]) continue;
    free_persons.push_back(static_cast<int>(i));
    free_person_boxes.push_back(persons[i]->box_px);
  }
  for (size_t j = 0; j < tracks.size(); ++j) {
    if (track_used[j]) continue;
    free_tracks.push_back(static_cast<int>(j));
    free_track_boxes.push_back(tracks[j]->box);
  }
  for (const auto& [a, b] : MatchByIoU(free_person_boxes, free_track_boxes, iou_threshold)) {
    matches.emplace_back(free_persons[a], free_tracks[b]);
  }
  return matches;
}

// The distances from a matched person's visible contacts to the nearest HOI point of its track.
struct HoiScore {
  std::vector<double> errors_px;  // contacts whose track had HOI points
  int contacts = 0, contacts_without_points = 0, hits = 0;

  void Add(const PersonRecord& person, const TrackedBox& track, double tolerance_px) {
    for (const ContactRecord& contact : person.contacts) {
      if (!contact.visible) continue;
      ++contacts;
      if (track.hoi_points_px.empty()) {
        ++contacts_without_points;
        continue;
      }
      double nearest_px = INFINITY;
      for (const cv::Point2f& q : track.hoi_points_px) {
        nearest_px = std::min(nearest_px, std::hypot(q.x - contact.u_px, q.y - contact.v_px));
      }
      errors_px.push_back(nearest_px);
      if (nearest_px <= tolerance_px) ++hits;
    }
  }
};

// IDF1's IDTP: one-to-one person-to-track assignment maximising the frames they overlap. With
// cost C - IDTP and limit C, each match changes the objective by -IDTP. The maps are keyed by
// person id, track id and (person, track) -> frames overlapping at the IoU threshold.
int IdTruePositives(const std::map<int, int>& person_boxes, const std::map<int, int>& track_boxes,
                    const std::map<std::pair<int, int>, int>& overlap_frames) {
  std::vector<int> person_ids, track_ids;
  for (const auto& entry : person_boxes) person_ids.push_back(entry.first);
  for (const auto& entry : track_boxes) track_ids.push_back(entry.first);
  int max_overlap = 0;
  for (const auto& entry : overlap_frames) max_overlap = std::max(max_overlap, entry.second);
  if (max_overlap == 0) return 0;
  const double c = max_overlap + 1.0;
  std::vector<std::vector<double>> cost(person_ids.size(), std::vector<double>(track_ids.size(), 2 * c + 1));
  for (const auto& [pair, count] : overlap_frames) {
    const size_t row = std::lower_bound(person_ids.begin(), person_ids.end(), pair.first) - person_ids.begin();
    const size_t col = std::lower_bound(track_ids.begin(), track_ids.end(), pair.second) - track_ids.begin();
    cost[row][col] = c - count;
  }
  int idtp = 0;
  for (const auto& [row, col] : LinearAssignment(cost, c).matches) {
    const auto it = overlap_frames.find({person_ids[row], track_ids[col]});
    if (it != overlap_frames.end()) idtp += it->second;
  }
  return idtp;
}

}  // namespace

TrackingMetricsOptions::TrackingMetricsOptions() { Table().FillDefaults(this); }

const OptionTable<TrackingMetricsOptions>& TrackingMetricsOptions::Table() {
  using O = TrackingMetricsOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("iou_threshold", &O::iou_threshold, 0.5, "", R::Any().Above(0).AtMost(1),
               "IoU a prediction needs with a person to match it")
          .Add("min_visible_fraction", &O::min_visible_fraction, 0, "", R::Closed(0, 1),
               "less visible persons are ignored: never missed, and a prediction on one is not a false positive")
          .Add("min_box_height_px", &O::min_box_height_px, 0, "px", R::Any().AtLeast(0),
               "persons whose visible box is lower are ignored likewise")
          .Add("hoi_tolerance_px", &O::hoi_tolerance_px, 3, "px", R::Any().AtLeast(0),
               "a contact this close to its nearest HOI point is a hit");
  return table;
}

std::string TrackingMetricsOptions::Check() const { return Table().FirstProblem(*this); }

nlohmann::json TrackingMetrics::ToJson() const {
  return {{"frames", frames},
          {"gt_boxes", gt_boxes},
          {"predicted_boxes", predicted_boxes},
          {"true_positives", true_positives},
          {"false_positives", false_positives},
          {"false_negatives", false_negatives},
          {"id_switches", id_switches},
          {"precision", JsonNumber(precision)},
          {"recall", JsonNumber(recall)},
          {"mota", JsonNumber(mota)},
          {"idtp", idtp},
          {"idfp", idfp},
          {"idfn", idfn},
          {"idf1", JsonNumber(idf1)},
          {"hoi_contacts", hoi_contacts},
          {"hoi_contacts_without_points", hoi_contacts_without_points},
          {"hoi_median_error_px", JsonNumber(hoi_median_error_px)},
          {"hoi_fraction_within_tolerance", JsonNumber(hoi_fraction_within_tolerance)}};
}

TrackingMetrics ComputeTrackingMetrics(const std::vector<FramePersons>& ground_truth,
                                       const std::vector<FrameTracks>& predicted,
                                       const TrackingMetricsOptions& options) {
  const std::string problem = options.Check();
  HOILCD_CHECK_MSG(problem.empty(), problem);
  std::map<int, FrameBoxes> frames = FramesOf(ground_truth, predicted);

  TrackingMetrics m;
  m.frames = static_cast<int>(frames.size());
  std::map<int, int> last_match;                      // person id -> track id of its latest match
  std::map<int, int> previous_frame_match;            // person id -> track id matched in the last frame
  std::map<std::pair<int, int>, int> overlap_frames;  // (person, track) -> frames at IoU >= thr
  std::map<int, int> person_boxes, track_boxes;
  HoiScore hoi;
  for (auto& [frame, boxes] : frames) {
    DropIgnored(options, &boxes);
    const std::vector<const PersonRecord*>& persons = boxes.persons;
    const std::vector<const TrackedBox*>& tracks = boxes.tracks;

    // IDF1 counts every (person, track) overlap, independently of the CLEAR MOT matching.
    for (const PersonRecord* p : persons) {
      ++person_boxes[p->id];
      for (const TrackedBox* t : tracks) {
        if (BoxIoU(p->box_px, t->box) >= options.iou_threshold) ++overlap_frames[{p->id, t->id}];
      }
    }
    for (const TrackedBox* t : tracks) ++track_boxes[t->id];

    const std::vector<std::pair<int, int>> matches =
        ClearMotMatches(boxes, previous_frame_match, options.iou_threshold);
    std::map<int, int> this_frame_match;
    for (const auto& [i, j] : matches) {
      const PersonRecord& person = *persons[i];
      const TrackedBox& track = *tracks[j];
      const auto last = last_match.find(person.id);
      if (last != last_match.end() && last->second != track.id) ++m.id_switches;
      last_match[person.id] = track.id;
      this_frame_match[person.id] = track.id;
      hoi.Add(person, track, options.hoi_tolerance_px);
    }
    previous_frame_match = std::move(this_frame_match);
    m.gt_boxes += static_cast<int>(persons.size());
    m.predicted_boxes += static_cast<int>(tracks.size());
    m.true_positives += static_cast<int>(matches.size());
    m.false_positives += static_cast<int>(tracks.size() - matches.size());
    m.false_negatives += static_cast<int>(persons.size() - matches.size());
  }

  if (m.true_positives + m.false_positives > 0) {
    m.precision = static_cast<double>(m.true_positives) / (m.true_positives + m.false_positives);
  }
  if (m.gt_boxes > 0) {
    m.recall = static_cast<double>(m.true_positives) / m.gt_boxes;
    m.mota = 1.0 - static_cast<double>(m.false_negatives + m.false_positives + m.id_switches) / m.gt_boxes;
  }
  m.idtp = IdTruePositives(person_boxes, track_boxes, overlap_frames);
  m.idfn = m.gt_boxes - m.idtp;
  m.idfp = m.predicted_boxes - m.idtp;
  if (m.gt_boxes + m.predicted_boxes > 0) {
    m.idf1 = 2.0 * m.idtp / (m.gt_boxes + m.predicted_boxes);
  }
  m.hoi_contacts = hoi.contacts;
  m.hoi_contacts_without_points = hoi.contacts_without_points;
  m.hoi_median_error_px = Median(hoi.errors_px);
  if (m.hoi_contacts > 0) {
    m.hoi_fraction_within_tolerance = static_cast<double>(hoi.hits) / m.hoi_contacts;
  }
  return m;
}

}  // namespace hoilcd
