#include "hoilcd/bench/front_ends.h"

#include <chrono>

#include "hoilcd/core/parallel.h"
#include "hoilcd/core/progress.h"

namespace hoilcd {
namespace {

using Clock = std::chrono::steady_clock;
double MsSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

// DLCD's front end over the sequence, in frame order (the tracker carries state).
void RunPersonFrontEnd(const Dataset& dataset, const FrontEndOptions& options, FrontEndOutput* out) {
  const int n = dataset.num_frames();
  out->hoi.assign(n, {});
  out->persons_ms.assign(n, 0.0);
  DlcdFrontEnd front_end(options.detector, options.tracker, options.hoi);
  ProgressReporter progress("persons", n, "frames");
  for (int f = 0; f < n; ++f) {
    const cv::Mat thermal = dataset.Thermal(f);
    const cv::Mat radiometric = dataset.RadiometricC(f);
    const auto t = Clock::now();
    out->hoi[f] = front_end.Process(thermal, radiometric);
    out->persons_ms[f] = MsSince(t);
    std::vector<Point2> points;
    for (const HoiFeature& h : out->hoi[f]) points.push_back(h.point);
    out->hoi_index.Add(points);
    FrameTracks ft;
    ft.frame = f;
    for (const Track& track : front_end.last_tracks()) {
      TrackedBox box{track.id, track.box, {}};
      for (const HoiFeature& h : out->hoi[f])
        if (h.track_id == track.id) box.hoi_points_px.push_back(h.point);
      ft.tracks.push_back(box);
    }
    out->tracks.push_back(ft);
    progress.Update();
  }
  progress.Done();
}

}  // namespace

FrontEndOutput RunFrontEnds(const Dataset& dataset, const std::set<FrontEnd>& needed, const FrontEndOptions& options) {
  FrontEndOutput out;
  out.ran = needed;
  out.thumbnails = ThumbnailIndex(options.thumbnail);
  const int n = dataset.num_frames();
  const bool keypoints = out.Ran(FrontEnd::kKeypoints), thumbnails = out.Ran(FrontEnd::kThumbnails);
  if (keypoints || thumbnails) {
    // Per-frame front ends: every frame on its own, results written by frame index.
    out.keypoints.assign(n, {});
    out.keypoints_ms.assign(n, 0.0);
    out.thumbnails_ms.assign(n, 0.0);
    std::vector<std::vector<float>> descriptors(n);
    ProgressReporter progress("features", n, "frames");
    ParallelFor(n, options.threads, [&](int64_t f) {
      const cv::Mat thermal = dataset.Thermal(static_cast<int>(f));
      if (keypoints) {
        const auto t = Clock::now();
        out.keypoints[f] = DetectKeypoints(thermal, options.keypoints);
        out.keypoints_ms[f] = MsSince(t);
      }
      if (thumbnails) {
        const auto t = Clock::now();
        descriptors[f] = ThumbnailDescriptor(thermal, options.thumbnail);
        out.thumbnails_ms[f] = MsSince(t);
      }
      progress.Update();
    });
    progress.Done();
    for (int f = 0; f < n; ++f) {
      if (keypoints) out.keypoint_index.Add(out.keypoints[f]);
      if (thumbnails) out.thumbnails.AddDescriptor(std::move(descriptors[f]));
    }
  }
  if (out.Ran(FrontEnd::kPersons)) RunPersonFrontEnd(dataset, options, &out);
  return out;
}

}  // namespace hoilcd
