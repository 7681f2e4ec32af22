// Cost of rendering paper_room frames against bare Embree (issue 2, "Must show"). Each
// iteration covers kPoses camera poses spread along the robot's route (SimulateRobot with the
// scene's options). BM_FullVsBareInterleaved gives the headline ratio: per pose it runs, back to
// back so that load from other processes hits all alike, (a) bare Embree — the renderer's
// 256×192 primary rays cast with rtcIntersect1 in a plain loop, hits stored, no shading — and
// the same rays as rtcIntersect16 packets, then (b) the full frame — FrameRenderer::Render +
// SensorModel::Apply with every effect the scene enables. Both sides use the same World, the
// same thread count and the same row chunks (ParallelForChunks, 8 rows). BM_Pipeline is (c), the
// whole per-frame work of `hoilcd render` (World::SetTime, render, sensor, T_true, persons
// ground truth, 8- and 16-bit PNG, EXR, checksums) without the disk; BM_PipelinePart times its
// pieces on one thread; BM_WorldSetTime times moving the articulated people alone. Counter x_bare = time / bare
// rtcIntersect1 time (wall; _cpu: process CPU time, all threads). A summary of ratios, frames per second and the
// projected time of the scene's 1996 frames follows the table. Run: build/bin/render_bench            (scene:
// DataDir()/scenes/paper_room.json)
#include <chrono>
#include <cstdio>
#include <ctime>
#include <map>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>
#include <opencv2/imgcodecs.hpp>

#include "bare_packets.h"
#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/dataset/exr_io.h"
#include "hoilcd/core/dataset/frame_encoding.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/sim/assets/data_dir.h"
#include "hoilcd/sim/render/renderer.h"
#include "hoilcd/sim/render/visibility.h"
#include "hoilcd/sim/scene/scene.h"
#include "hoilcd/sim/scene/scene_options.h"
#include "hoilcd/sim/sensor/sensor.h"

namespace hoilcd {
namespace {

constexpr int kPoses = 20;  // camera poses per iteration, evenly spread over the route

// Everything the benchmarks share, built once: the scene, its World and the route's poses.
struct Setup {
  Setup()
      : scene(LoadScene(DataDir() + "/scenes/paper_room.json")),
        world(scene, table),
        intrinsics(IntrinsicsFromScene(scene)) {
    const RobotRun run = SimulateSceneRobot(scene, world.obstacles());
    for (int i = 0; i < kPoses; ++i) {
      samples.push_back(run.samples[(2 * i + 1) * scene.frames / (2 * kPoses)]);
    }
    // Unit ray directions in the camera frame, as the renderer's pixel centres.
    for (int y = 0; y < intrinsics.height; ++y) {
      for (int x = 0; x < intrinsics.width; ++x) {
        cam_directions.push_back(intrinsics.Unproject(x, y).cast<float>().normalized());
      }
    }
  }
  Scene scene;
  BandRadianceTable table;
  World world;
  CameraIntrinsics intrinsics;
  std::vector<RobotSample> samples;
  std::vector<Eigen::Vector3f> cam_directions;
  std::map<std::string, double> seconds_per_frame;  // "bare/1" etc., from this run
};

Setup& Shared() {
  static Setup setup;
  return setup;
}

// Wall and process CPU seconds per frame measured around the benchmark loop (the last,
// reported, invocation wins). Process CPU time counts every thread, Embree's included.
class FrameClock {
 public:
  FrameClock() : wall_start_(std::chrono::steady_clock::now()), cpu_start_(std::clock()) {}
  double WallPerFrame(const benchmark::State& state) const {
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start_).count();
    return s / static_cast<double>(state.iterations() * kPoses);
  }
  double CpuPerFrame(const benchmark::State& state) const {
    const double s = static_cast<double>(std::clock() - cpu_start_) / CLOCKS_PER_SEC;
    return s / static_cast<double>(state.iterations() * kPoses);
  }

 private:
  std::chrono::steady_clock::time_point wall_start_;
  std::clock_t cpu_start_;
};

void Finish(benchmark::State& state, const std::string& kind, const FrameClock& clock) {
  Setup& s = Shared();
  const std::string threads = std::to_string(state.range(0));
  const double wall = clock.WallPerFrame(state), cpu = clock.CpuPerFrame(state);
  s.seconds_per_frame[kind + "/" + threads] = wall;
  s.seconds_per_frame[kind + "/" + threads + "/cpu"] = cpu;
  state.counters["ms_per_frame"] = 1e3 * wall;
  state.counters["cpu_ms_per_frame"] = 1e3 * cpu;
  state.counters["fps"] = 1.0 / wall;
  const auto bare = s.seconds_per_frame.find("bare/" + threads);
  if (kind != "bare" && bare != s.seconds_per_frame.end()) {
    state.counters["x_bare"] = wall / bare->second;
    state.counters["x_bare_cpu"] = cpu / s.seconds_per_frame.at("bare/" + threads + "/cpu");
  }
}

// Pose of every sample at one fixed world time, so (a) and (b) see identical geometry.
void FixWorldTime(Setup& s) { s.world.SetTime(s.samples.front().time_s); }

// Hits of bare Embree casts (kept so the casts cannot be optimised away).
// The renderer's primary rays, one rtcIntersect1 per pixel in a plain loop, rows split into the
// renderer's chunks of 8.
void CastBare(const Setup& s, const CameraPose& pose, int threads, BareHits* hits) {
  const int W = s.intrinsics.width, H = s.intrinsics.height;
  RTCScene scene = s.world.caster().embree_scene();
  const Rigid3 world_from_cam = pose.WorldFromCam();
  const Eigen::Matrix3f R = world_from_cam.rotation.toRotationMatrix().cast<float>();
  const Eigen::Vector3f o = world_from_cam.translation.cast<float>();
  ParallelForChunks(H, 8, threads, [&](int64_t y0, int64_t y1, int) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (int64_t i = y0 * W; i < y1 * W; ++i) {
      const Eigen::Vector3f d = R * s.cam_directions[i];
      RTCRayHit rh;
      rh.ray.org_x = o.x(), rh.ray.org_y = o.y(), rh.ray.org_z = o.z();
      rh.ray.dir_x = d.x(), rh.ray.dir_y = d.y(), rh.ray.dir_z = d.z();
      rh.ray.tnear = 0.0f;
      rh.ray.tfar = std::numeric_limits<float>::infinity();
      rh.ray.mask = 0xFFFFFFFFu;
      rh.ray.flags = 0;
      rh.ray.time = 0;
      rh.ray.id = 0;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(scene, &context, &rh);
      hits->distance[i] = rh.ray.tfar;
      hits->instance[i] = rh.hit.instID[0];
      hits->triangle[i] = rh.hit.primID;
    }
  });
  benchmark::DoNotOptimize(hits->distance.data());
}

void BM_BareEmbree(benchmark::State& state) {
  Setup& s = Shared();
  FixWorldTime(s);
  BareHits hits(s.intrinsics.width * s.intrinsics.height);
  FrameClock clock;
  for (auto _ : state) {
    for (const RobotSample& sample : s.samples) {
      CastBare(s, sample.camera, static_cast<int>(state.range(0)), &hits);
    }
  }
  Finish(state, "bare", clock);
}

// rtcIntersect16 runs only where the CPU has native 16-wide packets (the renderer falls back).
bool Native16(const Setup& s) {
  RTCDevice device = rtcGetSceneDevice(s.world.caster().embree_scene());
  const bool native = rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED);
  rtcReleaseDevice(device);  // rtcGetSceneDevice retains it
  return native;
}

void BM_BareEmbreePackets(benchmark::State& state) {
  Setup& s = Shared();
  if (!Native16(s)) {
    state.SkipWithError("no native 16-wide Embree packets on this CPU");
    return;
  }
  FixWorldTime(s);
  BareHits hits(s.intrinsics.width * s.intrinsics.height);
  FrameClock clock;
  for (auto _ : state) {
    for (const RobotSample& sample : s.samples) {
      CastBarePackets(s.world, s.intrinsics, s.cam_directions, sample.camera, static_cast<int>(state.range(0)), &hits);
    }
  }
  Finish(state, "bare_packets", clock);
}

// The headline ratio, robust to other load on a shared machine: per pose, bare rtcIntersect1,
// bare rtcIntersect16 and the full frame (Render + SensorModel::Apply) run back to back, each
// timed on its own (wall and process CPU), so load changes hit all three alike.
void BM_FullVsBareInterleaved(benchmark::State& state) {
  Setup& s = Shared();
  FixWorldTime(s);
  const int threads = static_cast<int>(state.range(0));
  const FrameRenderer renderer(s.world, s.intrinsics, RenderOptionsFromScene(s.scene, threads));
  SensorModel sensor(SensorOptionsFromScene(s.scene), s.intrinsics.width, s.intrinsics.height, s.scene.frame_rate_hz,
                     s.scene.seed, &s.table, threads);
  BareHits hits(s.intrinsics.width * s.intrinsics.height);
  const bool native16 = Native16(s);
  enum { kBare, kPackets, kRender, kSensor, kParts };
  double wall[kParts] = {}, cpu[kParts] = {};
  int frame = 0;
  for (auto _ : state) {
    for (const RobotSample& sample : s.samples) {
      cv::Mat radiance;
      for (int part = 0; part < kParts; ++part) {
        const auto wall_start = std::chrono::steady_clock::now();
        const std::clock_t cpu_start = std::clock();
        if (part == kBare) CastBare(s, sample.camera, threads, &hits);
        if (part == kPackets && native16)
          CastBarePackets(s.world, s.intrinsics, s.cam_directions, sample.camera, threads, &hits);
        if (part == kRender) radiance = renderer.Render(sample.camera).radiance;
        if (part == kSensor) benchmark::DoNotOptimize(sensor.Apply(frame++, radiance).data);
        wall[part] += std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
        cpu[part] += static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
      }
    }
  }
  const double frames = static_cast<double>(state.iterations() * kPoses);
  const double full_wall = wall[kRender] + wall[kSensor], full_cpu = cpu[kRender] + cpu[kSensor];
  state.counters["bare_ms"] = 1e3 * wall[kBare] / frames;
  state.counters["bare16_ms"] = 1e3 * wall[kPackets] / frames;
  state.counters["render_ms"] = 1e3 * wall[kRender] / frames;
  state.counters["sensor_ms"] = 1e3 * wall[kSensor] / frames;
  state.counters["x_bare"] = full_wall / wall[kBare];
  state.counters["x_bare_cpu"] = full_cpu / cpu[kBare];
  state.counters["x_bare16"] = full_wall / wall[kPackets];
  state.counters["x_bare16_cpu"] = full_cpu / cpu[kPackets];
  const std::string key = "interleaved/" + std::to_string(threads) + "/";
  s.seconds_per_frame[key + "bare"] = wall[kBare] / frames;
  s.seconds_per_frame[key + "bare/cpu"] = cpu[kBare] / frames;
  s.seconds_per_frame[key + "bare16"] = wall[kPackets] / frames;
  s.seconds_per_frame[key + "bare16/cpu"] = cpu[kPackets] / frames;
  s.seconds_per_frame[key + "render"] = wall[kRender] / frames;
  s.seconds_per_frame[key + "render/cpu"] = cpu[kRender] / frames;
  s.seconds_per_frame[key + "full"] = full_wall / frames;
  s.seconds_per_frame[key + "full/cpu"] = full_cpu / frames;
}

void BM_RenderOnly(benchmark::State& state) {
  Setup& s = Shared();
  FixWorldTime(s);
  const FrameRenderer renderer(s.world, s.intrinsics,
                               RenderOptionsFromScene(s.scene, static_cast<int>(state.range(0))));
  int edge_pixels = 0;
  FrameClock clock;
  for (auto _ : state) {
    for (const RobotSample& sample : s.samples) {
      const FrameBuffers frame = renderer.Render(sample.camera);
      edge_pixels += frame.edge_pixels;
      benchmark::DoNotOptimize(frame.radiance.data);
    }
  }
  Finish(state, "render", clock);
  state.counters["edge_px"] = static_cast<double>(edge_pixels) / (state.iterations() * kPoses);
}

void BM_FullFrame(benchmark::State& state) {
  Setup& s = Shared();
  FixWorldTime(s);
  const int threads = static_cast<int>(state.range(0));
  const FrameRenderer renderer(s.world, s.intrinsics, RenderOptionsFromScene(s.scene, threads));
  SensorModel sensor(SensorOptionsFromScene(s.scene), s.intrinsics.width, s.intrinsics.height, s.scene.frame_rate_hz,
                     s.scene.seed, &s.table, threads);
  int frame = 0;
  FrameClock clock;
  for (auto _ : state) {
    for (const RobotSample& sample : s.samples) {
      const cv::Mat t = sensor.Apply(frame++, renderer.Render(sample.camera).radiance);
      benchmark::DoNotOptimize(t.data);
    }
  }
  Finish(state, "full", clock);
}

cv::Mat ToFloat(const cv::Mat& m) {
  cv::Mat f;
  m.convertTo(f, CV_32F);
  return f;
}

// What RenderSequence does per frame, minus the file writes (checksums are computed as
// WriteDatasetFile does).
void BM_Pipeline(benchmark::State& state) {
  Setup& s = Shared();
  const int threads = static_cast<int>(state.range(0));
  const FrameRenderer renderer(s.world, s.intrinsics, RenderOptionsFromScene(s.scene, threads));
  const SensorOptions options = SensorOptionsFromScene(s.scene);
  SensorModel sensor(options, s.intrinsics.width, s.intrinsics.height, s.scene.frame_rate_hz, s.scene.seed, &s.table,
                     threads);
  int frame = 0;
  size_t bytes = 0;
  FrameClock clock;
  for (auto _ : state) {
    for (const RobotSample& sample : s.samples) {
      s.world.SetTime(sample.time_s);
      const FrameBuffers buffers = renderer.Render(sample.camera);
      const cv::Mat temperature = sensor.Apply(frame++, buffers.radiance);
      const cv::Mat ideal = sensor.IdealTemperature(buffers.radiance);
      const std::vector<PersonRecord> persons =
          VisiblePersons(s.world, s.intrinsics, sample.camera, buffers.instance, buffers.depth_m);
      const std::string files[3] = {EncodePng(ToDisplay8Bit(temperature, options.display_min_c, options.display_max_c)),
                                    EncodePng(ToCentikelvin16(temperature)),
                                    EncodeExr({{"T", temperature},
                                               {"T_true", ideal},
                                               {"Z", buffers.depth_m},
                                               {"id", ToFloat(buffers.instance)},
                                               {"class", ToFloat(buffers.class_id)}})};
      for (const std::string& f : files) {
        bytes += f.size();
        benchmark::DoNotOptimize(ChecksumOf(f));
      }
      benchmark::DoNotOptimize(persons.data());
    }
  }
  Finish(state, "pipeline", clock);
  state.counters["kB_per_frame"] = bytes / 1e3 / (state.iterations() * kPoses);
}

// Parts of the pipeline on their own (one thread, as RenderSequence runs them).
void BM_PipelinePart(benchmark::State& state, int part) {
  Setup& s = Shared();
  FixWorldTime(s);
  const FrameRenderer renderer(s.world, s.intrinsics, RenderOptionsFromScene(s.scene, 1));
  const SensorOptions options = SensorOptionsFromScene(s.scene);
  SensorModel sensor(options, s.intrinsics.width, s.intrinsics.height, s.scene.frame_rate_hz, s.scene.seed, &s.table,
                     1);
  std::vector<FrameBuffers> buffers;
  std::vector<cv::Mat> temperature;
  for (int i = 0; i < kPoses; ++i) {
    buffers.push_back(renderer.Render(s.samples[i].camera));
    temperature.push_back(sensor.Apply(i, buffers.back().radiance));
  }
  int frame = kPoses;
  size_t bytes = 0;
  FrameClock clock;
  for (auto _ : state) {
    for (int i = 0; i < kPoses; ++i) {
      std::string encoded;
      if (part == 0) {
        benchmark::DoNotOptimize(sensor.Apply(frame++, buffers[i].radiance).data);
      } else if (part == 1) {
        encoded = EncodePng(ToDisplay8Bit(temperature[i], options.display_min_c, options.display_max_c));
      } else if (part == 2) {
        encoded = EncodePng(ToCentikelvin16(temperature[i]));
      } else if (part == 5 || part == 6 || part == 7) {
        std::vector<uchar> png;
        const cv::Mat image = part == 7 ? ToDisplay8Bit(temperature[i], options.display_min_c, options.display_max_c)
                                        : ToCentikelvin16(temperature[i]);
        cv::imencode(".png", image, png, {cv::IMWRITE_PNG_COMPRESSION, part == 6 ? 3 : 1});
        encoded.assign(png.begin(), png.end());
      } else if (part == 3) {
        encoded = EncodeExr({{"T", temperature[i]},
                             {"T_true", sensor.IdealTemperature(buffers[i].radiance)},
                             {"Z", buffers[i].depth_m},
                             {"id", ToFloat(buffers[i].instance)},
                             {"class", ToFloat(buffers[i].class_id)}});
      } else {
        benchmark::DoNotOptimize(
            VisiblePersons(s.world, s.intrinsics, s.samples[i].camera, buffers[i].instance, buffers[i].depth_m));
      }
      bytes += encoded.size();
      benchmark::DoNotOptimize(encoded.data());
    }
  }
  if (bytes > 0) state.counters["kB_per_frame"] = bytes / 1e3 / (state.iterations() * kPoses);
  Finish(state, "part", clock);
}

void Threads(benchmark::internal::Benchmark* b) {
  b->Arg(1)->Arg(2)->ArgName("threads")->UseRealTime()->MeasureProcessCPUTime();
  b->Unit(benchmark::kMillisecond);
}

// Moving the people alone: World::SetTime at successive frame times (skeleton poses, activities,
// gait, 16 part transforms per person, props, the top-level BVH rebuilt by Commit).
void BM_WorldSetTime(benchmark::State& state) {
  Setup& s = Shared();
  double t = s.samples.front().time_s;
  FrameClock clock;
  for (auto _ : state) {
    for (int i = 0; i < kPoses; ++i) {
      t += 1.0 / s.scene.frame_rate_hz;
      s.world.SetTime(t);
    }
  }
  Finish(state, "settime", clock);
}

BENCHMARK(BM_FullVsBareInterleaved)->Apply(Threads)->MinTime(3.0);
BENCHMARK(BM_WorldSetTime)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BareEmbree)->Apply(Threads);
BENCHMARK(BM_BareEmbreePackets)->Apply(Threads);
BENCHMARK(BM_RenderOnly)->Apply(Threads);
BENCHMARK(BM_FullFrame)->Apply(Threads);
BENCHMARK(BM_Pipeline)->Apply(Threads);
BENCHMARK_CAPTURE(BM_PipelinePart, sensor_apply, 0)->Arg(1)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PipelinePart, png8, 1)->Arg(1)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PipelinePart, png8_level1, 7)->Arg(1)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PipelinePart, png16, 2)->Arg(1)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PipelinePart, png16_level1, 5)->Arg(1)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PipelinePart, png16_level3, 6)->Arg(1)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PipelinePart, exr_with_t_true, 3)->Arg(1)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PipelinePart, visible_persons, 4)->Arg(1)->UseRealTime()->Unit(benchmark::kMillisecond);

void PrintSummary() {
  const Setup& s = Shared();
  const auto get = [&](const std::string& key) {
    const auto it = s.seconds_per_frame.find(key);
    return it == s.seconds_per_frame.end() ? 0.0 : it->second;
  };
  std::printf(
      "\nSummary of this run (per frame over %d poses along the route; wall ms with process "
      "CPU ms in brackets; ratios wall / CPU):\n",
      kPoses);
  for (const char* t : {"1", "2"}) {
    const std::string key = std::string("interleaved/") + t + "/";
    const double bare = get(key + "bare"), bare_cpu = get(key + "bare/cpu");
    if (bare <= 0) continue;
    std::printf(
        "  %s thread(s): bare rtcIntersect1 %.2f [%.2f], rtcIntersect16 %.2f [%.2f]; "
        "render %.2f [%.2f]; render + sensor %.2f [%.2f] = %.2fx / %.2fx bare "
        "rtcIntersect1 (target <= 2x), %.2fx / %.2fx bare rtcIntersect16\n",
        t, 1e3 * bare, 1e3 * bare_cpu, 1e3 * get(key + "bare16"), 1e3 * get(key + "bare16/cpu"),
        1e3 * get(key + "render"), 1e3 * get(key + "render/cpu"), 1e3 * get(key + "full"), 1e3 * get(key + "full/cpu"),
        get(key + "full") / bare, get(key + "full/cpu") / bare_cpu, get(key + "full") / get(key + "bare16"),
        get(key + "full/cpu") / get(key + "bare16/cpu"));
  }
  for (const char* t : {"1", "2"}) {
    const double pipeline = get(std::string("pipeline/") + t);
    if (pipeline <= 0) continue;
    std::printf("  %s thread(s): whole per-frame pipeline %.2f [%.2f]\n", t, 1e3 * pipeline,
                1e3 * get(std::string("pipeline/") + t + "/cpu"));
  }
  const double pipeline2 = get("pipeline/2");
  const double full2 = get("interleaved/2/full");
  if (pipeline2 > 0 && full2 > 0) {
    std::printf(
        "  2 threads: %.1f frames/s (pipeline), %.1f frames/s (render + sensor); "
        "%d frames projected %.0f s (pipeline, without disk writes)\n",
        1.0 / pipeline2, 1.0 / full2, s.scene.frames, s.scene.frames * pipeline2);
  }
}

}  // namespace
}  // namespace hoilcd

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  hoilcd::PrintSummary();
  benchmark::Shutdown();
  return 0;
}
