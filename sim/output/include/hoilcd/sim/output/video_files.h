// What a render and a merge of its shards both write last: thermal.mp4, encoded from every
// uncompressed 8-bit frame in order, and in video mode (camera.video.enabled) the thermal PNGs
// replaced by its decoded frames. Both go through here, so they give the same bytes.
#pragma once

#include <functional>
#include <string>

#include <opencv2/core.hpp>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/dataset/video.h"

namespace hoilcd {

// Frame `frame` as it left the sensor model, 8-bit through the manifest's display window: from
// DIR/exr/NNNNNN.exr's T channel (float32, exactly what the thermal PNG was made from) when
// `from_exr`, else from DIR/thermal/NNNNNN.png (the caller makes sure it is still the
// uncompressed frame, not a decoded video frame).
cv::Mat UncompressedFrame(const std::string& dir, int frame, const DatasetManifest& manifest, bool from_exr);

// thermal.mp4 of frames 0..frames-1, each from frame_of(f), in order.
std::string EncodeVideo(const VideoOptions& video, const DatasetManifest& manifest, int frames,
                        const std::function<cv::Mat(int)>& frame_of);

// Writes `mp4` as DIR/thermal.mp4 when the manifest's outputs have video, and in video mode with
// thermal PNGs replaces every DIR/thermal/NNNNNN.png by its decoded frame (written on `threads`
// threads, synced as one batch); each file's checksum goes into the manifest.
void WriteVideoFiles(const std::string& dir, const std::string& mp4, const VideoOptions& video, int frames, int threads,
                     DatasetManifest* manifest);

}  // namespace hoilcd
