#include "hoilcd/sim/output/video_files.h"

#include <vector>

#include "hoilcd/core/dataset/exr_io.h"
#include "hoilcd/core/dataset/frame_encoding.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/parallel.h"

namespace hoilcd {

cv::Mat UncompressedFrame(const std::string& dir, int frame, const DatasetManifest& manifest, bool from_exr) {
  if (!from_exr) {
    const std::string path = dir + "/thermal/" + FrameFileName(frame, "png");
    return DecodeFramePng(ReadFileBytes(path), path, CV_8UC1, manifest.intrinsics);
  }
  const std::string path = dir + "/exr/" + FrameFileName(frame, "exr");
  for (const auto& [name, channel] : ReadExr(path, {manifest.intrinsics.width, manifest.intrinsics.height})) {
    if (name == "T") return ToDisplay8Bit(channel, manifest.window_min_c, manifest.window_max_c);
  }
  throw InputError(path, "no T channel");
}

std::string EncodeVideo(const VideoOptions& video, const DatasetManifest& manifest, int frames,
                        const std::function<cv::Mat(int)>& frame_of) {
  VideoEncoder encoder(video, manifest.intrinsics.width, manifest.intrinsics.height, manifest.frame_rate_hz);
  for (int f = 0; f < frames; ++f) encoder.Add(frame_of(f));
  return encoder.Finish();
}

void WriteVideoFiles(const std::string& dir, const std::string& mp4, const VideoOptions& video, int frames, int threads,
                     DatasetManifest* manifest) {
  if (manifest->outputs.video) WriteDatasetFile(dir, "thermal.mp4", mp4, manifest);
  if (!video.enabled || !manifest->outputs.thermal) return;
  const DecodedVideo decoded = DecodeVideo(mp4, dir + "/thermal.mp4", ResolveThreadCount(threads));
  HOILCD_CHECK_MSG(static_cast<int>(decoded.frames.size()) == frames,
                   "decoded " << decoded.frames.size() << " of " << frames << " frames");
  // Written in parallel, synced as one batch, listed in the manifest in order.
  std::vector<std::string> checksums(frames), paths(frames);
  ParallelFor(frames, ResolveThreadCount(threads), [&](int64_t f) {
    const std::string bytes = EncodePng(decoded.frames[f]);
    paths[f] = dir + "/thermal/" + FrameFileName(static_cast<int>(f), "png");
    WriteFileAtomicUnsynced(paths[f], bytes);
    checksums[f] = ChecksumOf(bytes);
  });
  SyncFiles(paths);
  for (int f = 0; f < frames; ++f) manifest->files["thermal/" + FrameFileName(f, "png")] = checksums[f];
}

}  // namespace hoilcd
