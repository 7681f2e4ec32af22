// detection_eval: how well DLCD's person detector and tracker find the people of a dataset, against
// persons.json, with the reasons for each miss. The front end reads what bench reads (decoded
// frames in video mode), people are scored as bench scores them (>= 20 % visible, box >= 16 px).
// Usage: detection_eval DATASET [FIRST_FRAME [END_FRAME]] [DETECTOR_OPTION=VALUE...] [--draw=DIR] [--u8]
// (--u8: read the 8-bit frames only, as in video mode, even when the dataset is not in video mode)
// (--draw: DIR/NNNNNN.png per frame with people, temperatures 20-37 degC and the detector's mask,
// ground-truth boxes green, detections red, scaled 3x)
// (options: the numeric PersonDetectorOptions fields listed in kNumericOptions below)
#include <algorithm>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "hoilcd/bench/evaluation/tracking_metrics.h"
#include "hoilcd/bench/methods/front_end_input.h"
#include "hoilcd/bench/methods/manifest_options.h"
#include "hoilcd/bench/runner/runner.h"
#include "hoilcd/core/dataset/exr_io.h"
#include "hoilcd/core/util/error.h"

namespace hoilcd {
namespace {

bool Scored(const PersonRecord& p, const TrackingMetricsOptions& o) {
  return p.visible_fraction >= o.min_visible_fraction && p.box_px.height >= o.min_box_height_px;
}

// The person's own pixels: the instance of the EXR 'id' channel whose pixel box is the person's box.
cv::Mat PersonPixels(const cv::Mat& ids, const cv::Mat& classes, int person_class, const cv::Rect2f& box) {
  std::map<int, cv::Rect> boxes;
  const cv::Rect r(box);
  for (int y = r.y; y < r.br().y && y < ids.rows; ++y) {
    for (int x = r.x; x < r.br().x && x < ids.cols; ++x) {
      if (static_cast<int>(classes.at<float>(y, x)) != person_class) continue;
      const int id = static_cast<int>(ids.at<float>(y, x));
      auto it = boxes.find(id);
      if (it == boxes.end())
        boxes[id] = cv::Rect(x, y, 1, 1);
      else
        it->second |= cv::Rect(x, y, 1, 1);
    }
  }
  int best = -1, best_area = -1;
  for (const auto& [id, b] : boxes) {
    const int area = (b & r).area();
    if (area > best_area) best = id, best_area = area;
  }
  cv::Mat mask = cv::Mat::zeros(ids.size(), CV_8U);
  for (int y = 0; y < ids.rows; ++y)
    for (int x = 0; x < ids.cols; ++x) mask.at<uint8_t>(y, x) = static_cast<int>(ids.at<float>(y, x)) == best ? 255 : 0;
  return mask;
}

// Detector options a run may override, to compare rule variants on the same frames.
void SetOption(PersonDetectorOptions* o, const std::string& assignment) {
  const size_t eq = assignment.find('=');
  const std::string name = assignment.substr(0, eq);
  const double v = std::stod(assignment.substr(eq + 1));
  const std::map<std::string, double*> doubles = {{"threshold_c", &o->threshold_c},
                                                  {"split_valley_ratio", &o->split_valley_ratio},
                                                  {"min_peak_ratio", &o->min_peak_ratio},
                                                  {"head_min_c", &o->head_min_c},
                                                  {"head_zone_ratio", &o->head_zone_ratio},
                                                  {"merge_min_overlap", &o->merge_min_overlap},
                                                  {"min_aspect_hw", &o->min_aspect_hw},
                                                  {"max_flat_top_fraction", &o->max_flat_top_fraction},
                                                  {"min_clothing_fraction", &o->min_clothing_fraction},
                                                  {"valley_tolerance_ratio", &o->valley_tolerance_ratio}};
  const std::map<std::string, int*> ints = {{"open_kernel_px", &o->open_kernel_px},
                                            {"close_kernel_px", &o->close_kernel_px},
                                            {"min_head_area_px", &o->min_head_area_px},
                                            {"min_split_width_px", &o->min_split_width_px},
                                            {"min_area_px", &o->min_area_px},
                                            {"min_height_px", &o->min_height_px},
                                            {"profile_smooth_px", &o->profile_smooth_px},
                                            {"min_top_skin_px", &o->min_top_skin_px}};
  if (doubles.count(name))
    *doubles.at(name) = v;
  else if (ints.count(name))
    *ints.at(name) = static_cast<int>(v);
  else
    throw InputError(assignment, "not a detector option this tool can set");
}

// Why people were missed and what false detections were on, counted over the frames.
struct MissTally {
  std::map<std::string, int> misses, false_positives;
  std::map<std::string, std::pair<int, int>> by_posture;  // posture -> (found, scored)
  double warm_fraction_sum = 0;
  int scored_people = 0;

  // One frame's raw detections `d` against its people (IoU at the scoring threshold, greedy by
  // IoU); `scored`: the people scored; ids, classes: the EXR channels (empty without scored people).
  void Add(const FramePersons& people, const std::vector<const PersonRecord*>& scored, const FrameTracks& d,
           const cv::Mat& temperature, const cv::Mat& ids, const cv::Mat& classes, int person_class,
           const PersonDetectorOptions& detector, const TrackingMetricsOptions& scoring) {
    for (const PersonRecord* p : scored) {
      ++scored_people;
      const cv::Mat own = PersonPixels(ids, classes, person_class, p->box_px);
      const int pixels = cv::countNonZero(own);
      const int warm = cv::countNonZero(own & (temperature >= detector.threshold_c));
      warm_fraction_sum += pixels ? static_cast<double>(warm) / pixels : 0;
      double best_iou = 0;
      const TrackedBox* best = nullptr;
      for (const TrackedBox& b : d.tracks) {
        const double iou = BoxIoU(b.box, p->box_px);
        if (iou > best_iou) best_iou = iou, best = &b;
      }
      auto& posture = by_posture[p->posture];
      ++posture.second;
      if (best_iou >= scoring.iou_threshold) {
        ++posture.first;
        continue;
      }
      if (pixels == 0 || warm < 0.3 * pixels) {
        ++misses["under 30 % of its pixels reach threshold_c"];
      } else if (best == nullptr || best_iou < 0.1) {
        ++misses["warm enough, no detection on it (rejected or too small)"];
      } else {
        // Merged with a neighbour (the detection's box covers another scored person) or cut.
        int others = 0;
        for (const PersonRecord* q : scored)
          if (q != p && BoxIoU(best->box, q->box_px) > 0.1) ++others;
        const double area_ratio = best->box.area() / std::max(1.0f, p->box_px.area());
        misses[others > 0       ? "merged with a neighbour"
               : area_ratio < 1 ? "detection covers part of it (cut/split)"
                                : "detection too large (joined other warm parts)"]++;
      }
    }
    for (const TrackedBox& b : d.tracks) {
      double best_iou = 0, best_any = 0;
      for (const PersonRecord& p : people.persons) {
        const double iou = BoxIoU(b.box, p.box_px);
        best_any = std::max(best_any, iou);
        if (Scored(p, scoring)) best_iou = std::max(best_iou, iou);
      }
      if (best_iou >= scoring.iou_threshold || best_any >= scoring.iou_threshold) continue;
      false_positives[best_any >= 0.1 ? "overlaps a person at IoU 0.1-0.5 (merge, part)" : "on no person (object)"]++;
    }
  }
};

// DIR/NNNNNN.png: temperatures 20-37 degC over the detector's mask, ground-truth boxes green,
// detections red, scaled 3x.
void DrawFrame(const std::string& draw_dir, int frame, const cv::Mat& temperature, const cv::Mat& detector_mask,
               const std::vector<const PersonRecord*>& scored, const FrameTracks& d) {
  cv::Mat grey, colour, mask;
  temperature.convertTo(grey, CV_8U, 255.0 / 17.0, -20.0 * 255.0 / 17.0);
  cv::applyColorMap(grey, colour, cv::COLORMAP_INFERNO);
  cv::cvtColor(detector_mask, mask, cv::COLOR_GRAY2BGR);
  cv::Mat both;
  cv::vconcat(colour, mask, both);
  cv::resize(both, both, cv::Size(), 3, 3, cv::INTER_NEAREST);
  for (int half = 0; half < 2; ++half) {
    const cv::Point2f shift(0, half * temperature.rows);
    for (const PersonRecord* p : scored)
      cv::rectangle(both, cv::Rect((p->box_px.tl() + shift) * 3, cv::Size2f(p->box_px.width * 3, p->box_px.height * 3)),
                    {0, 255, 0}, 1);
    for (const TrackedBox& b : d.tracks)
      cv::rectangle(both, cv::Rect((b.box.tl() + shift) * 3, cv::Size2f(b.box.width * 3, b.box.height * 3)),
                    {0, 0, 255}, 1);
  }
  cv::imwrite(draw_dir + "/" + FrameFileName(frame, "png"), both);
}

void PrintSummary(const TrackingMetrics& det, const TrackingMetrics& trk, const MissTally& tally,
                  const TrackingMetricsOptions& scoring) {
  std::printf("scored people %d; mean fraction of their pixels >= threshold_c %.3f\n", tally.scored_people,
              tally.scored_people ? tally.warm_fraction_sum / tally.scored_people : 0.0);
  std::printf("detections: precision %.3f recall %.3f (TP %d FP %d FN %d)\n", det.precision, det.recall,
              det.true_positives, det.false_positives, det.false_negatives);
  std::printf("tracks:     precision %.3f recall %.3f MOTA %.3f IDF1 %.3f id switches %d\n", trk.precision, trk.recall,
              trk.mota, trk.idf1, trk.id_switches);
  std::printf("HOI points: median %.2f px from the true contact, %.3f within %.0f px (%d contacts)\n",
              trk.hoi_median_error_px, trk.hoi_fraction_within_tolerance, scoring.hoi_tolerance_px, trk.hoi_contacts);
  std::printf("misses (raw detections, IoU < %.1f):\n", scoring.iou_threshold);
  for (const auto& [why, n] : tally.misses) std::printf("  %5d  %s\n", n, why.c_str());
  std::printf("false detections:\n");
  for (const auto& [why, n] : tally.false_positives) std::printf("  %5d  %s\n", n, why.c_str());
  std::printf("recall by posture:\n");
  for (const auto& [posture, n] : tally.by_posture)
    std::printf("  %-22s %.3f (%d of %d)\n", posture.c_str(), n.second ? double(n.first) / n.second : 0.0, n.first,
                n.second);
}

// The raw detections (ids f·100 + k) and the tracks with their HOI points of the front end's last frame.
void FrameOutputs(const DlcdFrontEnd& front_end, const std::vector<HoiFeature>& hoi, int f, FrameTracks* d,
                  FrameTracks* t) {
  *d = {f, {}};
  *t = {f, {}};
  for (size_t k = 0; k < front_end.last_detections().detections.size(); ++k) {
    d->tracks.push_back({static_cast<int>(f * 100 + k), front_end.last_detections().detections[k].box, {}});
  }
  for (const Track& track : front_end.last_tracks()) {
    TrackedBox box{track.id, track.box, {}};
    for (const HoiFeature& h : hoi)
      if (h.track_id == track.id) box.hoi_points_px.push_back(h.point);
    t->tracks.push_back(box);
  }
}

int Main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: detection_eval DATASET [FIRST_FRAME [END_FRAME]] [OPTION=VALUE...]\n");
    return 2;
  }
  const Dataset dataset = Dataset::Open(argv[1], Verify::kOnRead);
  std::vector<int> range;
  std::string draw_dir;
  bool u8_only = false;
  BenchOptions options = WithManifest(BenchOptions{}, dataset.manifest());
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind("--draw=", 0) == 0)
      draw_dir = arg.substr(7);
    else if (arg == "--u8")
      u8_only = true;
    else if (arg.find('=') != std::string::npos)
      SetOption(&options.detector, arg);
    else
      range.push_back(std::stoi(arg));
  }
  if (const std::string problem = options.detector.Check(); !problem.empty()) throw InputError("detector", problem);
  const int first = range.size() > 0 ? range[0] : 0;
  const int end = range.size() > 1 ? std::min(range[1], dataset.num_frames()) : dataset.num_frames();
  const TrackingMetricsOptions& scoring = options.tracking_metrics;
  const bool video_mode = u8_only || IsVideoMode(dataset);
  const int person_class = dataset.manifest().classes.at("person");
  DlcdFrontEnd front_end(options.detector, options.tracker, options.hoi);

  std::vector<FramePersons> truth;
  std::vector<FrameTracks> detected, tracked;
  MissTally tally;
  for (int f = first; f < end; ++f) {
    const FrontEndInput input = ReadFrontEndInput(dataset, f, video_mode, true);
    const std::vector<HoiFeature> hoi = front_end.Process(input.thermal_u8, input.radiometric_c);
    FrameTracks d, t;
    FrameOutputs(front_end, hoi, f, &d, &t);
    const FramePersons& people = dataset.persons().at(f);
    HOILCD_CHECK(people.frame == f);
    truth.push_back(people);
    std::vector<const PersonRecord*> scored;
    for (const PersonRecord& p : people.persons)
      if (Scored(p, scoring)) scored.push_back(&p);
    cv::Mat ids, classes, temperature = dataset.RadiometricC(f);
    if (!scored.empty()) {
      for (auto& [name, channel] : ReadDatasetExr(dataset, f)) {
        if (name == "id") ids = channel;
        if (name == "class") classes = channel;
      }
    }
    tally.Add(people, scored, d, temperature, ids, classes, person_class, options.detector, scoring);
    if (!draw_dir.empty() && !scored.empty()) {
      DrawFrame(draw_dir, f, temperature, front_end.last_detections().mask, scored, d);
    }
    detected.push_back(d);
    tracked.push_back(t);
  }
  std::printf("frames %d-%d of %s (%s)\n", first, end - 1, argv[1], video_mode ? "8-bit frames only" : "radiometric");
  PrintSummary(ComputeTrackingMetrics(truth, detected, scoring), ComputeTrackingMetrics(truth, tracked, scoring), tally,
               scoring);
  return 0;
}

}  // namespace
}  // namespace hoilcd

int main(int argc, char** argv) {
  try {
    return hoilcd::Main(argc, argv);
  } catch (const hoilcd::InputError& e) {
    std::fprintf(stderr, "detection_eval: %s\n", e.what());
    return 1;
  }
}
