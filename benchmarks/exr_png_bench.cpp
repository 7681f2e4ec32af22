// The dataset's frame encoders on real paper_room frames (issue 16, "Output path"): CPU ms and
// kB per frame of each OpenEXR compression (NONE, RLE, ZIPS, ZIP at zlib levels 1 and 4, PIZ)
// for two channel layouts -- all float32 (datasets before sim revision 9) and the dataset's
// (T, T_true float32; Z half; id, class uint) -- and of the 8- and 16-bit PNGs: hoilcd's
// libdeflate encoder (EncodeGreyPng, sim revision >= 13), OpenCV's default parameters (revisions
// 9-12) and zlib level 1 (before), then decoding them: DecodeGreyPng against OpenCV. Frames: kFrames poses
// spread along the route, each rendered and passed through the sensor model once, up front.
// After the table: the largest error of Z stored as half over those frames, in metres.
// Run: build/bin/exr_png_bench            (scene: DataDir()/scenes/paper_room.json)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <opencv2/imgcodecs.hpp>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/dataset/exr_io.h"
#include "hoilcd/core/dataset/frame_encoding.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/png.h"
#include "hoilcd/sim/assets/data_dir.h"
#include "hoilcd/sim/output/sequence.h"
#include "hoilcd/sim/render/renderer.h"
#include "hoilcd/sim/scene/scene.h"
#include "hoilcd/sim/scene/scene_options.h"
#include "hoilcd/sim/sensor/sensor.h"

namespace hoilcd {
namespace {

constexpr int kFrames = 20;  // frames, evenly spread over the route

struct Frame {
  cv::Mat temperature, ideal, depth_m, instance, class_id;
};

// The frames every benchmark encodes, rendered once.
struct Setup {
  Setup() : scene(LoadScene(DataDir() + "/scenes/paper_room.json")), world(scene, table) {
    const CameraIntrinsics intrinsics = IntrinsicsFromScene(scene);
    const RobotRun run = SimulateSceneRobot(scene, world.obstacles());
    world.PlanCrowd(run.samples);
    sensor_options = SensorOptionsFromScene(scene);
    const FrameRenderer renderer(world, intrinsics, RenderOptionsFromScene(scene, 0));
    for (int i = 0; i < kFrames; ++i) {
      const int f = (2 * i + 1) * scene.frames / (2 * kFrames);
      world.SetTime(run.samples[f].time_s);
      const FrameBuffers buffers = renderer.Render(run.samples[f].camera);
      // A fresh model per frame (the model takes frames in order); its noise is a frame's noise.
      SensorModel sensor(sensor_options, intrinsics.width, intrinsics.height, scene.frame_rate_hz, scene.seed, &table,
                         0);
      frames.push_back({sensor.Apply(0, buffers.radiance), sensor.IdealTemperature(buffers.radiance), buffers.depth_m,
                        buffers.instance, buffers.class_id});
    }
  }
  Scene scene;
  BandRadianceTable table;
  World world;
  SensorOptions sensor_options;
  std::vector<Frame> frames;
};

Setup& Shared() {
  static Setup setup;
  return setup;
}

cv::Mat As(const cv::Mat& m, int type) {
  cv::Mat out;
  m.convertTo(out, type);
  return out;
}

// All float32, as datasets were written before sim revision 9.
ExrChannels Float32Layout(const Frame& f) {
  return {{"T", f.temperature},
          {"T_true", f.ideal},
          {"Z", f.depth_m},
          {"id", As(f.instance, CV_32F)},
          {"class", As(f.class_id, CV_32F)}};
}

// The dataset's layout (FrameExrChannels): Z half, id and class uint.
ExrChannels DatasetLayout(const Frame& f) {
  return FrameExrChannels(f.temperature, f.ideal, f.depth_m, f.instance, f.class_id);
}

// Per-frame CPU time of the calling thread (encoders run on one thread each).
double ThreadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

void Report(benchmark::State& state, double cpu_s, size_t bytes) {
  const double frames = static_cast<double>(state.iterations()) * kFrames;
  state.counters["cpu_ms_per_frame"] = 1e3 * cpu_s / frames;
  state.counters["kB_per_frame"] = bytes / 1e3 / frames;
}

void BM_Exr(benchmark::State& state, ExrCompression compression, int zip_level, bool dataset_layout,
            bool openexr_rle = false) {
  Setup& s = Shared();
  std::vector<ExrChannels> channels;
  for (const Frame& f : s.frames) channels.push_back(dataset_layout ? DatasetLayout(f) : Float32Layout(f));
  size_t bytes = 0;
  double cpu_s = 0;
  for (auto _ : state) {
    for (const ExrChannels& c : channels) {
      const double start = ThreadCpuSeconds();
      const std::string encoded = EncodeExr(c, {compression, zip_level, openexr_rle});
      cpu_s += ThreadCpuSeconds() - start;
      bytes += encoded.size();
      benchmark::DoNotOptimize(encoded.data());
    }
  }
  Report(state, cpu_s, bytes);
}

// The frames as the dataset's 8- or 16-bit PNGs encode them.
std::vector<cv::Mat> PngImages(int bits) {
  Setup& s = Shared();
  std::vector<cv::Mat> images;
  for (const Frame& f : s.frames) {
    images.push_back(bits == 8
                         ? ToDisplay8Bit(f.temperature, s.sensor_options.display_min_c, s.sensor_options.display_max_c)
                         : ToCentikelvin16(f.temperature));
  }
  return images;
}

constexpr int kLibdeflate = -2;  // BM_Png's level for EncodeGreyPng

// bits 8 or 16; level kLibdeflate: EncodeGreyPng; -1: OpenCV's default parameters, else
// IMWRITE_PNG_COMPRESSION level.
void BM_Png(benchmark::State& state, int bits, int level) {
  const std::vector<cv::Mat> images = PngImages(bits);
  std::vector<int> params;
  if (level >= 0) params = {cv::IMWRITE_PNG_COMPRESSION, level};
  size_t bytes = 0;
  double cpu_s = 0;
  for (auto _ : state) {
    for (const cv::Mat& image : images) {
      std::vector<uchar> png;
      std::string grey;
      const double start = ThreadCpuSeconds();
      if (level == kLibdeflate)
        grey = EncodeGreyPng(image);
      else
        cv::imencode(".png", image, png, params);
      cpu_s += ThreadCpuSeconds() - start;
      bytes += png.size() + grey.size();  // one of them is empty
      benchmark::DoNotOptimize(png.data());
      benchmark::DoNotOptimize(grey.data());
    }
  }
  Report(state, cpu_s, bytes);
}

// Decoding the frames' PNGs (written by EncodeGreyPng): DecodeGreyPng (`fast`) or OpenCV.
void BM_PngDecode(benchmark::State& state, int bits, bool fast) {
  std::vector<std::string> files;
  for (const cv::Mat& image : PngImages(bits)) files.push_back(EncodeGreyPng(image));
  const int type = bits == 8 ? CV_8UC1 : CV_16UC1;
  const cv::Size image_size = Shared().frames.front().temperature.size();
  size_t bytes = 0;
  double cpu_s = 0;
  for (auto _ : state) {
    for (const std::string& file : files) {
      cv::Mat image;
      const double start = ThreadCpuSeconds();
      if (fast)
        HOILCD_CHECK(DecodeGreyPng(file, image_size.width, image_size.height, type, &image));
      else
        image = cv::imdecode(std::vector<uchar>(file.begin(), file.end()), cv::IMREAD_UNCHANGED);
      cpu_s += ThreadCpuSeconds() - start;
      bytes += file.size();
      benchmark::DoNotOptimize(image.data);
    }
  }
  Report(state, cpu_s, bytes);
}

void Unit(benchmark::internal::Benchmark* b) { b->Unit(benchmark::kMillisecond); }

BENCHMARK_CAPTURE(BM_Exr, float32_none, ExrCompression::kNone, 1, false)->Apply(Unit);
BENCHMARK_CAPTURE(BM_Exr, float32_rle, ExrCompression::kRle, 1, false)->Apply(Unit);
BENCHMARK_CAPTURE(BM_Exr, float32_zips1, ExrCompression::kZips, 1, false)->Apply(Unit);
BENCHMARK_CAPTURE(BM_Exr, float32_zip1, ExrCompression::kZip, 1, false)->Apply(Unit);
BENCHMARK_CAPTURE(BM_Exr, float32_zip4, ExrCompression::kZip, 4, false)->Apply(Unit);
BENCHMARK_CAPTURE(BM_Exr, float32_piz, ExrCompression::kPiz, 1, false)->Apply(Unit);
BENCHMARK_CAPTURE(BM_Exr, dataset_none, ExrCompression::kNone, 1, true)->Apply(Unit);
BENCHMARK_CAPTURE(BM_Exr, dataset_rle, ExrCompression::kRle, 1, true)->Apply(Unit);
BENCHMARK_CAPTURE(BM_Exr, dataset_rle_by_openexr, ExrCompression::kRle, 1, true, true)->Apply(Unit);
BENCHMARK_CAPTURE(BM_Exr, dataset_zips1, ExrCompression::kZips, 1, true)->Apply(Unit);
BENCHMARK_CAPTURE(BM_Exr, dataset_zip1, ExrCompression::kZip, 1, true)->Apply(Unit);
BENCHMARK_CAPTURE(BM_Exr, dataset_zip4, ExrCompression::kZip, 4, true)->Apply(Unit);
BENCHMARK_CAPTURE(BM_Exr, dataset_piz, ExrCompression::kPiz, 1, true)->Apply(Unit);
BENCHMARK_CAPTURE(BM_Png, png8_libdeflate, 8, kLibdeflate)->Apply(Unit);
BENCHMARK_CAPTURE(BM_Png, png8_default, 8, -1)->Apply(Unit);
BENCHMARK_CAPTURE(BM_Png, png8_level1, 8, 1)->Apply(Unit);
BENCHMARK_CAPTURE(BM_Png, png16_libdeflate, 16, kLibdeflate)->Apply(Unit);
BENCHMARK_CAPTURE(BM_Png, png16_default, 16, -1)->Apply(Unit);
BENCHMARK_CAPTURE(BM_Png, png16_level1, 16, 1)->Apply(Unit);
BENCHMARK_CAPTURE(BM_PngDecode, png8_decode_libdeflate, 8, true)->Apply(Unit);
BENCHMARK_CAPTURE(BM_PngDecode, png8_decode_opencv, 8, false)->Apply(Unit);
BENCHMARK_CAPTURE(BM_PngDecode, png16_decode_libdeflate, 16, true)->Apply(Unit);
BENCHMARK_CAPTURE(BM_PngDecode, png16_decode_opencv, 16, false)->Apply(Unit);

// The largest |Z as half - Z as float32| over the frames, and the depth range it was seen in.
void PrintHalfDepthError() {
  const Setup& s = Shared();
  double max_error_m = 0, max_depth_m = 0;
  for (const Frame& f : s.frames) {
    const cv::Mat back = As(As(f.depth_m, CV_16F), CV_32F);
    max_error_m = std::max(max_error_m, cv::norm(back, f.depth_m, cv::NORM_INF));
    double lo = 0, hi = 0;
    cv::minMaxLoc(f.depth_m, &lo, &hi);
    max_depth_m = std::max(max_depth_m, hi);
  }
  std::printf("Z as half: largest error %.5f m over depths up to %.2f m (%d frames)\n", max_error_m, max_depth_m,
              kFrames);
}

}  // namespace
}  // namespace hoilcd

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  hoilcd::PrintHalfDepthError();
  return 0;
}
