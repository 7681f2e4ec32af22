#include "hoilcd/bench/methods/front_ends.h"

#include <algorithm>
#include <chrono>

#include "hoilcd/bench/methods/front_end_input.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/core/util/progress.h"

namespace hoilcd {
namespace {

using Clock = std::chrono::steady_clock;
double MsSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

// Frames per block: the per-frame work runs over a block in parallel, then the tracker over it in
// order; a block's person masks (48 kB each at 256x192) are all that is held.
constexpr int kBlockFrames = 64;

// DLCD's tracking over one block after its detections: ByteTrack in frame order (the tracker
// carries state), then each frame's HOI points from its tracks in parallel.
void TrackBlock(int block, int size, const FrontEndOptions& options, ByteTracker* tracker,
                std::vector<PersonDetections>* detections, std::vector<std::vector<Track>>* tracks,
                FrontEndOutput* out) {
  for (int i = 0; i < size; ++i) {  // the tracker in frame order
    const auto t = Clock::now();
    (*tracks)[i] = tracker->Update((*detections)[i].detections);
    out->persons_ms[block + i] += MsSince(t);
  }
  ParallelFor(size, options.threads, [&](int64_t i) {  // each frame's HOI points from its tracks
    const int f = block + static_cast<int>(i);
    const auto t = Clock::now();
    out->hoi[f] = ExtractHoiFeatures((*detections)[i].mask, (*tracks)[i], options.hoi);
    out->persons_ms[f] += MsSince(t);
  });
  std::vector<std::vector<Point2>> points(size);
  for (int i = 0; i < size; ++i) {
    for (const HoiFeature& h : out->hoi[block + i]) points[i].push_back(h.point);
  }
  out->hoi_index.AddAll(points, options.threads);
  for (int i = 0; i < size; ++i) {
    const int f = block + i;
    FrameTracks ft;
    ft.frame = f;
    for (const Track& track : (*tracks)[i]) {
      TrackedBox box{track.id, track.box, {}};
      for (const HoiFeature& h : out->hoi[f])
        if (h.track_id == track.id) box.hoi_points_px.push_back(h.point);
      ft.tracks.push_back(box);
    }
    out->tracks.push_back(ft);
  }
}

}  // namespace

// One pass over the frames, block by block: each frame is read and decoded once, and its
// keypoints, thumbnail and person detections computed in parallel; then the block's tracking.
FrontEndOutput RunFrontEnds(const Dataset& dataset, const std::set<FrontEnd>& needed, const FrontEndOptions& options) {
  FrontEndOutput out;
  out.ran = needed;
  out.thumbnails = ThumbnailIndex(options.thumbnail);
  const int n = dataset.num_frames();
  const bool keypoints = out.Ran(FrontEnd::kKeypoints), thumbnails = out.Ran(FrontEnd::kThumbnails);
  const bool persons = out.Ran(FrontEnd::kPersons);
  if (!keypoints && !thumbnails && !persons) return out;
  if (keypoints) out.keypoints.assign(n, {});
  if (keypoints || thumbnails) {
    out.keypoints_ms.assign(n, 0.0);
    out.thumbnails_ms.assign(n, 0.0);
  }
  std::vector<std::vector<float>> descriptors(thumbnails ? n : 0);
  if (persons) {
    out.hoi.assign(n, {});
    out.persons_ms.assign(n, 0.0);
  }
  ByteTracker tracker(options.tracker);
  std::vector<PersonDetections> detections(persons ? kBlockFrames : 0);
  std::vector<std::vector<Track>> tracks(persons ? kBlockFrames : 0);
  ProgressReporter progress("front ends", n, "frames");
  const bool video_mode = IsVideoMode(dataset);
  // Without the tracker there is nothing to do in order: one block, no barriers.
  const int block_frames = persons ? kBlockFrames : std::max(n, 1);
  for (int block = 0; block < n; block += block_frames) {
    const int size = std::min(block_frames, n - block);
    ParallelFor(size, options.threads, [&](int64_t i) {
      const int f = block + static_cast<int>(i);
      const FrontEndInput input = ReadFrontEndInput(dataset, f, video_mode, /*detector=*/persons);
      if (keypoints) {
        const auto t = Clock::now();
        out.keypoints[f] = DetectKeypoints(input.thermal_u8, options.keypoints);
        out.keypoints_ms[f] = MsSince(t);
      }
      if (thumbnails) {
        const auto t = Clock::now();
        descriptors[f] = ThumbnailDescriptor(input.thermal_u8, options.thumbnail);
        out.thumbnails_ms[f] = MsSince(t);
      }
      if (persons) {
        const auto t = Clock::now();
        detections[i] = DetectPersons(input.thermal_u8, input.radiometric_c, options.detector);
        out.persons_ms[f] = MsSince(t);
      }
    });
    if (persons) TrackBlock(block, size, options, &tracker, &detections, &tracks, &out);
    progress.Update(size);
  }
  progress.Done();
  if (keypoints) out.keypoint_index.AddAll(out.keypoints, options.threads);
  for (std::vector<float>& d : descriptors) out.thumbnails.AddDescriptor(std::move(d));
  return out;
}

}  // namespace hoilcd
