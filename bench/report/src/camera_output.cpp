#include "hoilcd/bench/report/camera_output.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "hoilcd/bench/methods/front_end_input.h"
#include "hoilcd/core/dataset/exr_io.h"
#include "hoilcd/core/dataset/frame_encoding.h"
#include "hoilcd/core/dataset/video.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/core/util/sizes.h"

namespace hoilcd {
namespace {

constexpr double kIdenticalPsnrDb = 100.0;  // cv::PSNR's value for identical images

double PatchMean(const cv::Mat& image, int x0, int y0, int size) {
  return cv::mean(image(cv::Rect(x0, y0, size, size)))[0];
}

// Corners minus centre of a CV_32F image, each a size×size patch mean.
double CornerMinusCentre(const cv::Mat& image, int size) {
  const int w = image.cols - size, h = image.rows - size;
  const double corners = (PatchMean(image, 0, 0, size) + PatchMean(image, w, 0, size) + PatchMean(image, 0, h, size) +
                          PatchMean(image, w, h, size)) /
                         4.0;
  return corners - PatchMean(image, w / 2, h / 2, size);
}

// One compared frame: its lens shading (T - T_true, corners minus centre) and how its video
// frame compares with the uncompressed 8-bit frame.
struct FrameComparison {
  bool compared = false, shaded = false, same_as_video = false;
  double shading_k = 0, psnr_db = 0;
};

// Frames marked by a freeze event; counts the events and the frames whose radiometric PNG
// repeats the one before (same checksum) into *stats.
std::vector<bool> FrozenFrames(const Dataset& dataset, CameraOutputStats* stats) {
  const DatasetManifest& m = dataset.manifest();
  const int frames = dataset.num_frames();
  std::vector<bool> frozen(static_cast<size_t>(frames), false);
  for (const DatasetEvent& e : dataset.events()) {
    if (e.type != "freeze") continue;
    ++stats->freeze_events;
    frozen[static_cast<size_t>(e.frame)] = true;
  }
  for (int f = 1; f < frames; ++f) {
    const auto now = m.files.find("radiometric/" + FrameFileName(f, "png"));
    const auto before = m.files.find("radiometric/" + FrameFileName(f - 1, "png"));
    if (now != m.files.end() && before != m.files.end()) stats->frozen_frames += now->second == before->second;
  }
  return frozen;
}

// The decoded thermal.mp4; stats->video_problem says why it cannot be compared (empty: it can).
DecodedVideo ReadVideo(const Dataset& dataset, int threads, CameraOutputStats* stats) {
  DecodedVideo video;
  const std::string video_path = dataset.dir() + "/thermal.mp4";
  try {
    video = DecodeVideo(dataset.ReadFile("thermal.mp4"), video_path, threads);
    stats->video_frames = static_cast<int>(video.frames.size());
    if (stats->video_frames != dataset.num_frames()) {
      stats->video_problem = video_path + ": " + std::to_string(stats->video_frames) + " video frames for " +
                             std::to_string(dataset.num_frames()) + " frames";
    }
  } catch (const InputError& e) {
    stats->video_problem = e.what();
  }
  return video;
}

// Frame f compared; `video` empty when it cannot be compared. Not compared without its EXR.
FrameComparison CompareFrame(const Dataset& dataset, int f, bool frozen, const DecodedVideo* video, int patch_px) {
  FrameComparison sample;
  cv::Mat t, t_true;
  ExrChannels exr;
  try {
    exr = ReadDatasetExr(dataset, f);
  } catch (const InputError&) {
    return sample;  // the EXRs are optional for readers (Dataset::Open needs only the PNGs)
  }
  for (const auto& [name, channel] : exr) {
    if (name == "T") t = channel;
    if (name == "T_true") t_true = channel;
  }
  if (t.empty() || t_true.empty()) return sample;
  sample.compared = true;
  const int patch = std::min({patch_px, t.cols / 2, t.rows / 2});
  // A frozen frame's T is an earlier view of the scene than its T_true: no shading there.
  sample.shaded = !frozen;
  if (sample.shaded) sample.shading_k = CornerMinusCentre(t - t_true, patch);
  if (video != nullptr) {
    const DatasetManifest& m = dataset.manifest();
    const cv::Mat uncompressed = ToDisplay8Bit(t, m.window_min_c, m.window_max_c);
    sample.psnr_db = cv::PSNR(video->frames[f], uncompressed);
    sample.same_as_video = cv::norm(dataset.Thermal(f), video->frames[f], cv::NORM_INF) == 0.0;
  }
  return sample;
}

}  // namespace

CameraOutputOptions::CameraOutputOptions() { Table().FillDefaults(this); }

const OptionTable<CameraOutputOptions>& CameraOutputOptions::Table() {
  using O = CameraOutputOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("max_frames_compared", &O::max_frames_compared, 200, "frames", R::Closed(1, kMaxFrames),
               "frames decoded and compared at most (evenly spaced)")
          .Add("patch_px", &O::patch_px, 8, "px", R::Closed(1, 64), "side of the corner and centre patches for shading")
          .Add("threads", &O::threads, 0, "", R::Any().AtLeast(0), "decoding and comparing threads (0: every core)");
  return table;
}

std::string CameraOutputOptions::Check() const { return Table().FirstProblem(*this); }

CameraOutputStats MeasureCameraOutput(const Dataset& dataset, const CameraOutputOptions& options) {
  const std::string problem = options.Check();
  HOILCD_CHECK_MSG(problem.empty(), problem);
  const int frames = dataset.num_frames();
  CameraOutputStats stats;
  stats.video_mode = IsVideoMode(dataset);
  const std::vector<bool> frozen = FrozenFrames(dataset, &stats);
  const DecodedVideo video = ReadVideo(dataset, options.threads, &stats);
  const bool video_ok = stats.video_problem.empty();

  // The evenly spaced frames are compared in parallel, each into its own slot, then summed in
  // frame order.
  const int step = std::max(1, (frames + options.max_frames_compared - 1) / options.max_frames_compared);
  std::vector<int> sampled;
  for (int f = 0; f < frames; f += step) sampled.push_back(f);
  std::vector<FrameComparison> samples(sampled.size());
  ParallelFor(static_cast<int64_t>(sampled.size()), options.threads, [&](int64_t i) {
    const int f = sampled[static_cast<size_t>(i)];
    samples[static_cast<size_t>(i)] =
        CompareFrame(dataset, f, frozen[static_cast<size_t>(f)], video_ok ? &video : nullptr, options.patch_px);
  });
  std::vector<double> psnr_db, shading_k;
  bool thermal_is_video = video_ok;
  for (const FrameComparison& sample : samples) {
    if (!sample.compared) continue;
    ++stats.frames_compared;
    if (sample.shaded) shading_k.push_back(sample.shading_k);
    if (video_ok) {
      psnr_db.push_back(sample.psnr_db);
      thermal_is_video = thermal_is_video && sample.same_as_video;
    }
  }
  stats.frames_shading = static_cast<int>(shading_k.size());
  stats.thermal_is_video = thermal_is_video && !psnr_db.empty();
  if (!psnr_db.empty()) {
    double sum = 0.0;
    for (double p : psnr_db) sum += std::min(p, kIdenticalPsnrDb);
    stats.psnr_mean_db = sum / static_cast<double>(psnr_db.size());
    stats.psnr_min_db = std::min(*std::min_element(psnr_db.begin(), psnr_db.end()), kIdenticalPsnrDb);
  }
  if (!shading_k.empty()) {
    double sum = 0.0;
    for (double s : shading_k) sum += s;
    stats.shading_mean_k = sum / static_cast<double>(shading_k.size());
    std::vector<double> sorted = shading_k;
    std::sort(sorted.begin(), sorted.end());
    stats.shading_p90_k = sorted[static_cast<size_t>(0.9 * static_cast<double>(sorted.size() - 1))];
  }
  return stats;
}

InspectSection CameraOutputSection(const CameraOutputStats& s) {
  InspectSection section{"camera_output", "Camera output (video, lens shading, FFC freezes)", {}};
  section.figures = {
      NumberFigure("video_mode", "video mode (methods read the decoded video)", s.video_mode ? 1 : 0, ""),
      NumberFigure("video_readable", "thermal.mp4 decodes to one frame per frame", s.video_problem.empty() ? 1 : 0, ""),
      NumberFigure("video_frames", "video frames", s.video_frames, ""),
      NumberFigure("psnr_mean_db", "video vs uncompressed 8-bit frames, PSNR mean", s.psnr_mean_db, "dB"),
      NumberFigure("psnr_min_db", "video vs uncompressed 8-bit frames, PSNR worst", s.psnr_min_db, "dB"),
      NumberFigure("thermal_is_video", "thermal PNGs are the decoded video frames", s.thermal_is_video ? 1 : 0, ""),
      NumberFigure("frames_compared", "frames compared", s.frames_compared, ""),
      NumberFigure("shading_mean_k", "lens shading, corner minus centre of T - T_true, mean", s.shading_mean_k, "K"),
      NumberFigure("shading_p90_k", "lens shading, corner minus centre, 90th percentile", s.shading_p90_k, "K"),
      NumberFigure("freeze_events", "frames frozen by FFCs (events.json)", s.freeze_events, ""),
      NumberFigure("frozen_frames", "frames repeating the previous frame (radiometric)", s.frozen_frames, ""),
  };
  return section;
}

}  // namespace hoilcd
