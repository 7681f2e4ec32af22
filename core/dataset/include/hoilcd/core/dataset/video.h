// The dataset's thermal.mp4: 8-bit frames encoded as H.264 in an MP4 container through FFmpeg's
// libraries (libavcodec/libavformat, x264), and decoded back. All libav use lives in video.cpp.
// Output bytes depend only on the frames and the options (one encoder thread, bit-exact flags).
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <opencv2/core.hpp>

#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

// Defaults resemble a handheld thermal camera's recording (HIKMICRO Pocket2 / FLIR-style MP4):
// a real-time embedded encoder, keyframe every second, no B-frames, moderate quality.
struct VideoOptions {
  bool enabled;        // video mode: the thermal PNGs are the decoded video frames
  int crf;             // x264 constant rate factor (used when bitrate_kbps is 0)
  int bitrate_kbps;    // target average bitrate, kbit/s (0: constant quality, crf)
  int gop_frames;      // frames between keyframes (25: 1 s at 25 Hz)
  std::string preset;  // x264 speed/quality preset (ultrafast … veryslow)

  VideoOptions();  // the registered defaults
  // Every field once: JSON name (the scene's /camera/video), unit, default, range, description.
  static const OptionTable<VideoOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

// "" when an MP4 can carry this frame rate (1–240 Hz, a ratio of whole numbers with a
// denominator up to 1001, e.g. 25 or 30000/1001), else what is wrong.
std::string VideoFrameRateProblem(double frame_rate_hz);
// "" when H.264 4:2:0 can carry this frame size (even width and height), else what is wrong.
std::string VideoFrameSizeProblem(int width, int height);

// Encodes CV_8UC1 frames of one size, in order, into MP4 bytes (the gray value is the luma,
// full range; chroma is neutral). Presentation time of frame k is k / frame_rate.
class VideoEncoder {
 public:
  // HOILCD_CHECKs the options, size and frame rate (callers check user input beforehand).
  VideoEncoder(const VideoOptions& options, int width, int height, double frame_rate_hz);
  ~VideoEncoder();
  VideoEncoder(const VideoEncoder&) = delete;
  VideoEncoder& operator=(const VideoEncoder&) = delete;

  void Add(const cv::Mat& gray);
  // Flushes the encoder, writes the trailer and returns the whole file. Call once.
  std::string Finish();
  int frames_added() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

struct DecodedVideo {
  std::string codec;  // e.g. "h264"
  int width = 0, height = 0;
  double frame_rate_hz = 0;
  std::vector<cv::Mat> frames;  // CV_8UC1, in presentation order
};

// Decodes an MP4 (bytes as written by VideoEncoder) into 8-bit frames (the luma plane), on
// `threads` decoder threads (0: every core; H.264 decoding is bit-exact at any count).
// Throws InputError(path_for_errors, ...) when the bytes are not a readable video.
DecodedVideo DecodeVideo(std::string_view mp4_bytes, const std::string& path_for_errors, int threads = 1);

}  // namespace hoilcd
