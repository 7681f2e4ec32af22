#include "hoilcd/core/dataset/video.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <mutex>
#include <sstream>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavformat/avio.h>
#include <libavutil/error.h>
#include <libavutil/log.h>
#include <libavutil/mem.h>
#include <libavutil/opt.h>
}

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/parallel.h"

namespace hoilcd {
namespace {

constexpr int kIoBufferBytes = 64 * 1024;
const char* const kPresets[] = {"ultrafast", "superfast", "veryfast", "faster",  "fast",
                                "medium",    "slow",      "slower",   "veryslow"};

// RAII owners of the libav objects used here.
struct CodecContextFree {
  void operator()(AVCodecContext* c) const { avcodec_free_context(&c); }
};
struct FrameFree {
  void operator()(AVFrame* f) const { av_frame_free(&f); }
};
struct PacketFree {
  void operator()(AVPacket* p) const { av_packet_free(&p); }
};
struct IoContextFree {
  void operator()(AVIOContext* io) const {
    if (io == nullptr) return;
    av_freep(&io->buffer);
    avio_context_free(&io);
  }
};
struct OutputFormatFree {
  void operator()(AVFormatContext* f) const { avformat_free_context(f); }
};
struct InputFormatClose {
  void operator()(AVFormatContext* f) const { avformat_close_input(&f); }
};
using CodecContextPtr = std::unique_ptr<AVCodecContext, CodecContextFree>;
using FramePtr = std::unique_ptr<AVFrame, FrameFree>;
using PacketPtr = std::unique_ptr<AVPacket, PacketFree>;
using IoContextPtr = std::unique_ptr<AVIOContext, IoContextFree>;

std::string AvError(int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, text, sizeof(text));
  return text;
}

// libav (and x264) log to stderr; hoilcd reports problems itself, so their log is silenced.
void QuietLibav() {
  static std::once_flag once;
  std::call_once(once, [] { av_log_set_level(AV_LOG_QUIET); });
}

// A growable in-memory file for the muxer (which seeks back to write sizes) and the demuxer.
struct MemoryFile {
  std::string bytes;
  int64_t position = 0;

  static int Write(void* opaque, uint8_t* buf, int size) {
    auto* file = static_cast<MemoryFile*>(opaque);
    const size_t end = static_cast<size_t>(file->position) + static_cast<size_t>(size);
    if (end > file->bytes.size()) file->bytes.resize(end);
    std::memcpy(&file->bytes[static_cast<size_t>(file->position)], buf, static_cast<size_t>(size));
    file->position = static_cast<int64_t>(end);
    return size;
  }
  static int Read(void* opaque, uint8_t* buf, int size) {
    auto* file = static_cast<MemoryFile*>(opaque);
    const int64_t left = static_cast<int64_t>(file->bytes.size()) - file->position;
    if (left <= 0) return AVERROR_EOF;
    const int n = static_cast<int>(std::min<int64_t>(left, size));
    std::memcpy(buf, file->bytes.data() + file->position, static_cast<size_t>(n));
    file->position += n;
    return n;
  }
  static int64_t Seek(void* opaque, int64_t offset, int whence) {
    auto* file = static_cast<MemoryFile*>(opaque);
    const int64_t size = static_cast<int64_t>(file->bytes.size());
    if (whence & AVSEEK_SIZE) return size;
    int64_t target = offset;
    switch (whence & ~AVSEEK_FORCE) {
      case SEEK_SET:
        break;
      case SEEK_CUR:
        target += file->position;
        break;
      case SEEK_END:
        target += size;
        break;
      default:
        return AVERROR(EINVAL);
    }
    if (target < 0) return AVERROR(EINVAL);
    file->position = target;
    return target;
  }
};

IoContextPtr NewIoContext(MemoryFile* file, bool write) {
  auto* buffer = static_cast<unsigned char*>(av_malloc(kIoBufferBytes));
  HOILCD_CHECK_MSG(buffer != nullptr, "out of memory");
  AVIOContext* io = avio_alloc_context(buffer, kIoBufferBytes, write ? 1 : 0, file, write ? nullptr : &MemoryFile::Read,
                                       write ? &MemoryFile::Write : nullptr, &MemoryFile::Seek);
  if (io == nullptr) {
    av_free(buffer);
    HOILCD_CHECK_MSG(false, "avio_alloc_context failed");
  }
  return IoContextPtr(io);
}

AVRational FrameRate(double frame_rate_hz) { return av_d2q(frame_rate_hz, 1000000); }

}  // namespace

VideoOptions::VideoOptions() { Table().FillDefaults(this); }

const OptionTable<VideoOptions>& VideoOptions::Table() {
  using O = VideoOptions;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("enabled", &O::enabled, false, "video mode: the thermal PNGs are the decoded frames of thermal.mp4")
          .Add("crf", &O::crf, 23, "", OptionRange::Closed(0, 51),
               "x264 constant rate factor (used when bitrate_kbps is 0)")
          .Add("bitrate_kbps", &O::bitrate_kbps, 0, "kbit/s", OptionRange::Closed(0, 100000),
               "target average bitrate (0: constant quality, crf)")
          .Add("gop_frames", &O::gop_frames, 25, "frames", OptionRange::Closed(1, 600), "frames between keyframes")
          .Add("preset", &O::preset, "veryfast", std::vector<std::string>(std::begin(kPresets), std::end(kPresets)),
               "x264 speed/quality preset");
  return table;
}

std::string VideoOptions::Check() const { return Table().FirstProblem(*this); }

std::string VideoFrameRateProblem(double frame_rate_hz) {
  const AVRational rate = FrameRate(frame_rate_hz);
  const bool exact = rate.den > 0 && rate.den <= 1001 && std::abs(av_q2d(rate) - frame_rate_hz) <= 1e-9 * frame_rate_hz;
  if (frame_rate_hz >= 1.0 && frame_rate_hz <= 240.0 && exact) return "";
  std::ostringstream out;
  out << "thermal.mp4 needs a frame rate in [1, 240] Hz that is a ratio of whole numbers with a "
         "denominator up to 1001, e.g. 25 or 29.97002997 (got "
      << frame_rate_hz << ")";
  return out.str();
}

std::string VideoFrameSizeProblem(int width, int height) {
  if (width % 2 == 0 && height % 2 == 0) return "";
  return "thermal.mp4 (H.264, 4:2:0) needs an even width and height (got " + std::to_string(width) + "x" +
         std::to_string(height) + ")";
}

struct VideoEncoder::State {
  MemoryFile file;
  IoContextPtr io;
  std::unique_ptr<AVFormatContext, OutputFormatFree> format;
  CodecContextPtr codec;
  FramePtr frame;
  PacketPtr packet;
  AVStream* stream = nullptr;  // owned by format
  int frames_added = 0;
  bool finished = false;

  // Sends `input` (nullptr: flush) and writes every packet the encoder returns.
  void Encode(const AVFrame* input) {
    int rc = avcodec_send_frame(codec.get(), input);
    HOILCD_CHECK_MSG(rc >= 0, "avcodec_send_frame: " << AvError(rc));
    for (;;) {
      rc = avcodec_receive_packet(codec.get(), packet.get());
      if (rc == AVERROR(EAGAIN) || rc == AVERROR_EOF) return;
      HOILCD_CHECK_MSG(rc >= 0, "avcodec_receive_packet: " << AvError(rc));
      av_packet_rescale_ts(packet.get(), codec->time_base, stream->time_base);
      packet->stream_index = stream->index;
      rc = av_interleaved_write_frame(format.get(), packet.get());  // takes the packet's data
      HOILCD_CHECK_MSG(rc >= 0, "av_interleaved_write_frame: " << AvError(rc));
    }
  }
};

VideoEncoder::VideoEncoder(const VideoOptions& options, int width, int height, double frame_rate_hz)
    : state_(std::make_unique<State>()) {
  QuietLibav();
  const std::string problem = options.Check();
  HOILCD_CHECK_MSG(problem.empty(), problem);
  HOILCD_CHECK_MSG(VideoFrameSizeProblem(width, height).empty(), width << "x" << height);
  HOILCD_CHECK_MSG(VideoFrameRateProblem(frame_rate_hz).empty(), "frame rate " << frame_rate_hz);
  State& s = *state_;

  const AVCodec* h264 = avcodec_find_encoder_by_name("libx264");
  HOILCD_CHECK_MSG(h264 != nullptr, "this FFmpeg has no libx264 encoder");
  s.codec.reset(avcodec_alloc_context3(h264));
  HOILCD_CHECK_MSG(s.codec != nullptr, "avcodec_alloc_context3 failed");
  const AVRational rate = FrameRate(frame_rate_hz);
  AVCodecContext& c = *s.codec;
  c.width = width;
  c.height = height;
  c.pix_fmt = AV_PIX_FMT_YUV420P;
  c.color_range = AVCOL_RANGE_JPEG;  // gray 0–255 is the luma as is: no range squeeze
  c.time_base = av_inv_q(rate);
  c.framerate = rate;
  c.gop_size = options.gop_frames;
  c.max_b_frames = 0;  // a camera's real-time encoder: no B-frames
  c.thread_count = 1;  // one x264 thread: its output then never depends on the machine
  c.flags |= AV_CODEC_FLAG_BITEXACT | AV_CODEC_FLAG_GLOBAL_HEADER;
  av_opt_set(c.priv_data, "preset", options.preset.c_str(), 0);
  if (options.bitrate_kbps > 0) {
    c.bit_rate = static_cast<int64_t>(options.bitrate_kbps) * 1000;
  } else {
    av_opt_set_double(c.priv_data, "crf", options.crf, 0);
  }
  // Fixed keyframe cadence (no scene-cut keyframes), as a camera records. No macroblock tree:
  // x264 0.164's AVX-512 macroblock tree reads uninitialised memory on small frames, so its
  // bytes varied from run to run; without it they are the same from SSSE3 to AVX-512.
  av_opt_set(c.priv_data, "x264-params", "scenecut=0:mbtree=0", 0);
  int rc = avcodec_open2(s.codec.get(), h264, nullptr);
  HOILCD_CHECK_MSG(rc >= 0, "avcodec_open2(libx264): " << AvError(rc));

  AVFormatContext* format = nullptr;
  rc = avformat_alloc_output_context2(&format, nullptr, "mp4", nullptr);
  HOILCD_CHECK_MSG(rc >= 0 && format != nullptr, "avformat_alloc_output_context2: " << AvError(rc));
  s.format.reset(format);
  s.io = NewIoContext(&s.file, /*write=*/true);
  s.format->pb = s.io.get();
  s.format->flags |= AVFMT_FLAG_BITEXACT;  // no library version strings in the file
  s.stream = avformat_new_stream(s.format.get(), nullptr);
  HOILCD_CHECK_MSG(s.stream != nullptr, "avformat_new_stream failed");
  s.stream->time_base = c.time_base;
  s.stream->avg_frame_rate = rate;
  rc = avcodec_parameters_from_context(s.stream->codecpar, s.codec.get());
  HOILCD_CHECK_MSG(rc >= 0, "avcodec_parameters_from_context: " << AvError(rc));
  rc = avformat_write_header(s.format.get(), nullptr);
  HOILCD_CHECK_MSG(rc >= 0, "avformat_write_header: " << AvError(rc));

  s.frame.reset(av_frame_alloc());
  s.packet.reset(av_packet_alloc());
  HOILCD_CHECK_MSG(s.frame != nullptr && s.packet != nullptr, "out of memory");
  s.frame->format = c.pix_fmt;
  s.frame->width = width;
  s.frame->height = height;
  s.frame->color_range = AVCOL_RANGE_JPEG;
  rc = av_frame_get_buffer(s.frame.get(), 0);
  HOILCD_CHECK_MSG(rc >= 0, "av_frame_get_buffer: " << AvError(rc));
}

VideoEncoder::~VideoEncoder() = default;

int VideoEncoder::frames_added() const { return state_->frames_added; }

void VideoEncoder::Add(const cv::Mat& gray) {
  State& s = *state_;
  HOILCD_CHECK_MSG(!s.finished, "VideoEncoder::Add after Finish");
  HOILCD_CHECK_MSG(gray.type() == CV_8UC1 && gray.cols == s.codec->width && gray.rows == s.codec->height,
                   "expected CV_8UC1 " << s.codec->width << "x" << s.codec->height);
  int rc = av_frame_make_writable(s.frame.get());  // the encoder may still hold the last one
  HOILCD_CHECK_MSG(rc >= 0, "av_frame_make_writable: " << AvError(rc));
  AVFrame& f = *s.frame;
  for (int y = 0; y < gray.rows; ++y) {
    std::memcpy(f.data[0] + static_cast<ptrdiff_t>(y) * f.linesize[0], gray.ptr<uint8_t>(y),
                static_cast<size_t>(gray.cols));
  }
  for (int plane = 1; plane <= 2; ++plane) {
    for (int y = 0; y < gray.rows / 2; ++y) {
      std::memset(f.data[plane] + static_cast<ptrdiff_t>(y) * f.linesize[plane], 128,
                  static_cast<size_t>(gray.cols / 2));
    }
  }
  f.pts = s.frames_added++;
  s.Encode(&f);
}

std::string VideoEncoder::Finish() {
  State& s = *state_;
  HOILCD_CHECK_MSG(!s.finished, "VideoEncoder::Finish called twice");
  s.finished = true;
  s.Encode(nullptr);
  const int rc = av_write_trailer(s.format.get());
  HOILCD_CHECK_MSG(rc >= 0, "av_write_trailer: " << AvError(rc));
  avio_flush(s.io.get());
  return std::move(s.file.bytes);
}

DecodedVideo DecodeVideo(std::string_view mp4_bytes, const std::string& path_for_errors, int threads) {
  QuietLibav();
  auto fail = [&](const std::string& what) {
    throw InputError(path_for_errors, "not a readable thermal video: " + what);
  };
  MemoryFile file;
  file.bytes.assign(mp4_bytes.data(), mp4_bytes.size());
  IoContextPtr io = NewIoContext(&file, /*write=*/false);
  AVFormatContext* raw = avformat_alloc_context();
  HOILCD_CHECK_MSG(raw != nullptr, "out of memory");
  raw->pb = io.get();
  int rc = avformat_open_input(&raw, nullptr, nullptr, nullptr);  // frees raw on failure
  if (rc < 0) fail("cannot open the container (" + AvError(rc) + ")");
  std::unique_ptr<AVFormatContext, InputFormatClose> format(raw);
  rc = avformat_find_stream_info(format.get(), nullptr);
  if (rc < 0) fail("cannot read stream information (" + AvError(rc) + ")");
  const AVCodec* decoder = nullptr;
  const int stream_index = av_find_best_stream(format.get(), AVMEDIA_TYPE_VIDEO, -1, -1, &decoder, 0);
  if (stream_index < 0 || decoder == nullptr) fail("no video stream");
  const AVStream* stream = format->streams[stream_index];
  CodecContextPtr codec(avcodec_alloc_context3(decoder));
  HOILCD_CHECK_MSG(codec != nullptr, "out of memory");
  rc = avcodec_parameters_to_context(codec.get(), stream->codecpar);
  if (rc < 0) fail("bad codec parameters (" + AvError(rc) + ")");
  codec->thread_count = ResolveThreadCount(threads);
  codec->thread_type = FF_THREAD_FRAME | FF_THREAD_SLICE;
  rc = avcodec_open2(codec.get(), decoder, nullptr);
  if (rc < 0) fail("cannot open the decoder (" + AvError(rc) + ")");

  DecodedVideo video;
  video.codec = decoder->name;
  video.width = codec->width;
  video.height = codec->height;
  video.frame_rate_hz = av_q2d(stream->avg_frame_rate);
  PacketPtr packet(av_packet_alloc());
  FramePtr frame(av_frame_alloc());
  HOILCD_CHECK_MSG(packet != nullptr && frame != nullptr, "out of memory");
  auto drain = [&] {
    for (;;) {
      const int r = avcodec_receive_frame(codec.get(), frame.get());
      if (r == AVERROR(EAGAIN) || r == AVERROR_EOF) return;
      if (r < 0) fail("decoding failed (" + AvError(r) + ")");
      const AVPixelFormat pix = static_cast<AVPixelFormat>(frame->format);
      if ((pix != AV_PIX_FMT_YUV420P && pix != AV_PIX_FMT_YUVJ420P) || frame->width != video.width ||
          frame->height != video.height) {
        fail("expected 8-bit 4:2:0 frames of " + std::to_string(video.width) + "x" + std::to_string(video.height) +
             " px");
      }
      cv::Mat gray(frame->height, frame->width, CV_8UC1);
      for (int y = 0; y < frame->height; ++y) {
        std::memcpy(gray.ptr<uint8_t>(y), frame->data[0] + static_cast<ptrdiff_t>(y) * frame->linesize[0],
                    static_cast<size_t>(frame->width));
      }
      video.frames.push_back(gray);
      av_frame_unref(frame.get());
    }
  };
  for (;;) {
    rc = av_read_frame(format.get(), packet.get());
    if (rc == AVERROR_EOF) break;
    if (rc < 0) fail("cannot read a packet (" + AvError(rc) + ")");
    if (packet->stream_index == stream_index) {
      rc = avcodec_send_packet(codec.get(), packet.get());
      if (rc < 0) fail("the decoder rejected a packet (" + AvError(rc) + ")");
      drain();
    }
    av_packet_unref(packet.get());
  }
  avcodec_send_packet(codec.get(), nullptr);
  drain();
  return video;
}

}  // namespace hoilcd
