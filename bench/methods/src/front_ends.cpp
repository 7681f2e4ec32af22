#include "hoilcd/bench/methods/front_ends.h"

#include <algorithm>
#include <chrono>

#include "hoilcd/bench/methods/front_end_input.h"
#include "hoilcd/core/util/error.h"
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
// carries state), then each frame's HOI points from its tracks in parallel. At a later recording
// run's first frame (run_starts) the robot was carried to its dock hours later: the tracker drops
// every track, so none carries over, and its ids count on, so they stay unique.
void TrackBlock(int block, int size, const FrontEndOptions& options, const std::vector<bool>& run_starts,
                ByteTracker* tracker, std::vector<PersonDetections>* detections,
                std::vector<std::vector<Track>>* tracks, FrontEndOutput* out) {
  for (int i = 0; i < size; ++i) {  // the tracker in frame order
    if (block + i > 0 && run_starts[block + i]) tracker->DropTracks();
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

// The oracle front ends of frame f, from the dataset's ground truth (no order between frames).
void RunOracles(const Dataset& dataset, int f, const FrontEndOptions& options, FrontEndOutput* out) {
  const bool ideal = out->Ran(FrontEnd::kIdealKeypoints), persons = out->Ran(FrontEnd::kTruePersons);
  if (!ideal && !persons) return;
  const GroundTruthInput input = ReadGroundTruthInput(dataset, f, ideal, persons);
  if (ideal) {
    const auto t = Clock::now();
    out->ideal_keypoints[f] = DetectKeypoints(input.ideal_u8, options.keypoints);
    out->ideal_keypoints_ms[f] = MsSince(t);
  }
  if (persons) {
    const FramePersons& people = dataset.persons()[f];
    HOILCD_CHECK_MSG(people.frame == f, "persons.json lists frame " << people.frame << " at " << f);
    const auto t = Clock::now();
    out->true_hoi[f] = ExtractHoiFeatures(input.person_mask, GroundTruthTracks(people), options.hoi);
    out->true_persons_ms[f] = MsSince(t);
  }
}

// The oracles' point sets per frame into their retrieval indexes.
void IndexOracles(const FrontEndOptions& options, FrontEndOutput* out) {
  if (out->Ran(FrontEnd::kIdealKeypoints)) out->ideal_keypoint_index.AddAll(out->ideal_keypoints, options.threads);
  if (!out->Ran(FrontEnd::kTruePersons)) return;
  std::vector<std::vector<Point2>> points(out->true_hoi.size());
  for (size_t f = 0; f < points.size(); ++f) {
    for (const HoiFeature& h : out->true_hoi[f]) points[f].push_back(h.point);
  }
  out->true_hoi_index.AddAll(points, options.threads);
}

// Sizes the per-frame outputs of the front ends that run.
void SizeOutputs(int n, FrontEndOutput* out) {
  if (out->Ran(FrontEnd::kKeypoints)) out->keypoints.assign(n, {});
  if (out->Ran(FrontEnd::kKeypoints) || out->Ran(FrontEnd::kThumbnails)) {
    out->keypoints_ms.assign(n, 0.0);
    out->thumbnails_ms.assign(n, 0.0);
  }
  if (out->Ran(FrontEnd::kPersons)) {
    out->hoi.assign(n, {});
    out->persons_ms.assign(n, 0.0);
  }
  if (out->Ran(FrontEnd::kIdealKeypoints)) {
    out->ideal_keypoints.assign(n, {});
    out->ideal_keypoints_ms.assign(n, 0.0);
  }
  if (out->Ran(FrontEnd::kTruePersons)) {
    out->true_hoi.assign(n, {});
    out->true_persons_ms.assign(n, 0.0);
  }
}

}  // namespace

std::vector<std::string> GroundTruthOutputs(FrontEnd front_end) {
  switch (front_end) {
    case FrontEnd::kIdealKeypoints:
      return {"exr"};
    case FrontEnd::kTruePersons:
      return {"exr", "persons"};
    default:
      return {};
  }
}

// One pass over the frames, block by block: each frame is read and decoded once, and its
// keypoints, thumbnail, person detections and oracles computed in parallel; then the block's tracking.
FrontEndOutput RunFrontEnds(const Dataset& dataset, const std::set<FrontEnd>& needed, const FrontEndOptions& options) {
  FrontEndOutput out;
  out.ran = needed;
  out.thumbnails = ThumbnailIndex(options.thumbnail);
  const int n = dataset.num_frames();
  const bool keypoints = out.Ran(FrontEnd::kKeypoints), thumbnails = out.Ran(FrontEnd::kThumbnails);
  const bool persons = out.Ran(FrontEnd::kPersons);
  if (needed.empty()) return out;
  SizeOutputs(n, &out);
  // The camera's frames, for the front ends that read them (the oracles read the ground truth).
  const bool camera = keypoints || thumbnails || persons;
  std::vector<std::vector<float>> descriptors(thumbnails ? n : 0);
  ByteTracker tracker(options.tracker);
  std::vector<bool> run_starts(n, false);
  for (const RunRecord& r : dataset.runs()) run_starts[r.first_frame] = true;
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
      RunOracles(dataset, f, options, &out);
      if (!camera) return;
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
    if (persons) TrackBlock(block, size, options, run_starts, &tracker, &detections, &tracks, &out);
    progress.Update(size);
  }
  progress.Done();
  if (keypoints) out.keypoint_index.AddAll(out.keypoints, options.threads);
  IndexOracles(options, &out);
  for (std::vector<float>& d : descriptors) out.thumbnails.AddDescriptor(std::move(d));
  return out;
}

}  // namespace hoilcd
