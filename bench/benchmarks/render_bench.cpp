// Cost of rendering paper_room frames against bare Embree, measured in one run (issue 2, "Must
// show"): (a) bare Embree — the same 256×192 primary rays cast with rtcIntersect1 in a plain
// loop, hits stored, no shading; (b) a full frame — FrameRenderer::Render + SensorModel::Apply
// with every effect the scene enables; (c) the whole per-frame pipeline of `hoilcd render`
// (World::SetTime, render, sensor, T_true, persons ground truth, 8-bit and 16-bit PNG, EXR,
// checksums) without the disk. Each iteration renders kPoses camera poses spread along the
// robot's route (SimulateRobot with the scene's options). Both sides run on the same number of
// threads with the same row chunks (ParallelForChunks, 8 rows). Counter x_bare = time / bare
// time of the same thread count in this run. After the table, a summary prints the ratios, the
// frames per second and the projected time of the scene's 1996 frames.
// Run: build/bench/render_bench            (scene: HOILCD_SOURCE_DIR/scenes/paper_room.json)
#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>

#include <chrono>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "hoilcd/core/dataset.h"
#include "hoilcd/core/parallel.h"
#include "hoilcd/sim/exr_io.h"
#include "hoilcd/sim/renderer.h"
#include "hoilcd/sim/scene.h"
#include "hoilcd/sim/scene_options.h"
#include "hoilcd/sim/sensor.h"
#include "hoilcd/sim/visibility.h"

namespace hoilcd {
namespace {

constexpr int kPoses = 20;  // camera poses per iteration, evenly spread over the route

// Everything the benchmarks share, built once: the scene, its World and the route's poses.
struct Setup {
  Setup()
      : scene(LoadScene(std::string(HOILCD_SOURCE_DIR) + "/scenes/paper_room.json")),
        world(scene, table),
        intrinsics(IntrinsicsFromScene(scene)) {
    const RobotRun run = SimulateRobot(TricycleOptionsFromScene(scene), RouteOptionsFromScene(scene),
                                       OdometryOptionsFromScene(scene), world.obstacles(),
                                       scene.frame_rate_hz, scene.seed);
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

// Seconds per frame measured around the benchmark loop (the last, reported, invocation wins).
class FrameClock {
 public:
  FrameClock() : start_(std::chrono::steady_clock::now()) {}
  double SecondsPerFrame(const benchmark::State& state) const {
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    return s / static_cast<double>(state.iterations() * kPoses);
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

void Finish(benchmark::State& state, const std::string& kind, double seconds_per_frame) {
  Setup& s = Shared();
  const std::string threads = std::to_string(state.range(0));
  s.seconds_per_frame[kind + "/" + threads] = seconds_per_frame;
  state.counters["ms_per_frame"] = 1e3 * seconds_per_frame;
  state.counters["fps"] = 1.0 / seconds_per_frame;
  const auto bare = s.seconds_per_frame.find("bare/" + threads);
  if (kind != "bare" && bare != s.seconds_per_frame.end()) {
    state.counters["x_bare"] = seconds_per_frame / bare->second;
  }
}

// Pose of every sample at one fixed world time, so (a) and (b) see identical geometry.
void FixWorldTime(Setup& s) { s.world.SetTime(s.samples.front().time_s); }

void BM_BareEmbree(benchmark::State& state) {
  Setup& s = Shared();
  FixWorldTime(s);
  const int threads = static_cast<int>(state.range(0));
  const int W = s.intrinsics.width, H = s.intrinsics.height;
  RTCScene scene = s.world.caster().embree_scene();
  std::vector<float> distance(W * H);
  std::vector<unsigned> instance(W * H), triangle(W * H);
  FrameClock clock;
  for (auto _ : state) {
    for (const RobotSample& sample : s.samples) {
      const Rigid3 world_from_cam = sample.camera.WorldFromCam();
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
          distance[i] = rh.ray.tfar;
          instance[i] = rh.hit.instID[0];
          triangle[i] = rh.hit.primID;
        }
      });
      benchmark::DoNotOptimize(distance.data());
      benchmark::DoNotOptimize(instance.data());
      benchmark::DoNotOptimize(triangle.data());
    }
  }
  Finish(state, "bare", clock.SecondsPerFrame(state));
}

// The same rays as 4×4-pixel packets with rtcIntersect16 (coherent), as the renderer casts them:
// the strongest bare-Embree baseline.
void BM_BareEmbreePackets(benchmark::State& state) {
  Setup& s = Shared();
  FixWorldTime(s);
  const int threads = static_cast<int>(state.range(0));
  const int W = s.intrinsics.width, H = s.intrinsics.height;
  RTCScene scene = s.world.caster().embree_scene();
  std::vector<float> distance(W * H);
  std::vector<unsigned> instance(W * H), triangle(W * H);
  FrameClock clock;
  for (auto _ : state) {
    for (const RobotSample& sample : s.samples) {
      const Rigid3 world_from_cam = sample.camera.WorldFromCam();
      const Eigen::Matrix3f R = world_from_cam.rotation.toRotationMatrix().cast<float>();
      const Eigen::Vector3f o = world_from_cam.translation.cast<float>();
      ParallelForChunks(H, 8, threads, [&](int64_t y0, int64_t y1, int) {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        alignas(64) int valid[16];
        alignas(64) RTCRayHit16 rh;
        for (int64_t by = y0; by < y1; by += 4) {
          for (int bx = 0; bx < W; bx += 4) {
            for (int k = 0; k < 16; ++k) {
              const Eigen::Vector3f d = R * s.cam_directions[(by + k / 4) * W + bx + k % 4];
              valid[k] = -1;
              rh.ray.org_x[k] = o.x(), rh.ray.org_y[k] = o.y(), rh.ray.org_z[k] = o.z();
              rh.ray.dir_x[k] = d.x(), rh.ray.dir_y[k] = d.y(), rh.ray.dir_z[k] = d.z();
              rh.ray.tnear[k] = 0.0f;
              rh.ray.tfar[k] = std::numeric_limits<float>::infinity();
              rh.ray.mask[k] = 0xFFFFFFFFu;
              rh.ray.flags[k] = 0;
              rh.ray.time[k] = 0;
              rh.ray.id[k] = 0;
              rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
              rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
            }
            rtcIntersect16(valid, scene, &context, &rh);
            for (int k = 0; k < 16; ++k) {
              const int64_t i = (by + k / 4) * W + bx + k % 4;
              distance[i] = rh.ray.tfar[k];
              instance[i] = rh.hit.instID[0][k];
              triangle[i] = rh.hit.primID[k];
            }
          }
        }
      });
      benchmark::DoNotOptimize(distance.data());
      benchmark::DoNotOptimize(instance.data());
      benchmark::DoNotOptimize(triangle.data());
    }
  }
  Finish(state, "bare_packets", clock.SecondsPerFrame(state));
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
  Finish(state, "render", clock.SecondsPerFrame(state));
  state.counters["edge_px"] = static_cast<double>(edge_pixels) / (state.iterations() * kPoses);
}

void BM_FullFrame(benchmark::State& state) {
  Setup& s = Shared();
  FixWorldTime(s);
  const int threads = static_cast<int>(state.range(0));
  const FrameRenderer renderer(s.world, s.intrinsics, RenderOptionsFromScene(s.scene, threads));
  SensorModel sensor(SensorOptionsFromScene(s.scene), s.intrinsics.width, s.intrinsics.height,
                     s.scene.frame_rate_hz, s.scene.seed, &s.table, threads);
  int frame = 0;
  FrameClock clock;
  for (auto _ : state) {
    for (const RobotSample& sample : s.samples) {
      const cv::Mat t = sensor.Apply(frame++, renderer.Render(sample.camera).radiance);
      benchmark::DoNotOptimize(t.data);
    }
  }
  Finish(state, "full", clock.SecondsPerFrame(state));
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
  SensorModel sensor(options, s.intrinsics.width, s.intrinsics.height, s.scene.frame_rate_hz,
                     s.scene.seed, &s.table, threads);
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
          VisiblePersons(s.world, s.intrinsics, sample.camera, buffers.instance);
      const std::string files[3] = {
          EncodePng(ToDisplay8Bit(temperature, options.display_min_c, options.display_max_c)),
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
  Finish(state, "pipeline", clock.SecondsPerFrame(state));
  state.counters["kB_per_frame"] = bytes / 1e3 / (state.iterations() * kPoses);
}

// Parts of the pipeline on their own (one thread, as RenderSequence runs them).
void BM_PipelinePart(benchmark::State& state, int part) {
  Setup& s = Shared();
  FixWorldTime(s);
  const FrameRenderer renderer(s.world, s.intrinsics, RenderOptionsFromScene(s.scene, 1));
  const SensorOptions options = SensorOptionsFromScene(s.scene);
  SensorModel sensor(options, s.intrinsics.width, s.intrinsics.height, s.scene.frame_rate_hz,
                     s.scene.seed, &s.table, 1);
  std::vector<FrameBuffers> buffers;
  std::vector<cv::Mat> temperature;
  for (int i = 0; i < kPoses; ++i) {
    buffers.push_back(renderer.Render(s.samples[i].camera));
    temperature.push_back(sensor.Apply(i, buffers.back().radiance));
  }
  int frame = kPoses;
  FrameClock clock;
  for (auto _ : state) {
    for (int i = 0; i < kPoses; ++i) {
      if (part == 0) {
        benchmark::DoNotOptimize(sensor.Apply(frame++, buffers[i].radiance).data);
      } else if (part == 1) {
        benchmark::DoNotOptimize(
            EncodePng(ToDisplay8Bit(temperature[i], options.display_min_c, options.display_max_c)));
      } else if (part == 2) {
        benchmark::DoNotOptimize(EncodePng(ToCentikelvin16(temperature[i])));
      } else if (part == 3) {
        benchmark::DoNotOptimize(EncodeExr({{"T", temperature[i]},
                                            {"T_true", sensor.IdealTemperature(buffers[i].radiance)},
                                            {"Z", buffers[i].depth_m},
                                            {"id", ToFloat(buffers[i].instance)},
                                            {"class", ToFloat(buffers[i].class_id)}}));
      } else {
        benchmark::DoNotOptimize(
            VisiblePersons(s.world, s.intrinsics, s.samples[i].camera, buffers[i].instance));
      }
    }
  }
  Finish(state, "part", clock.SecondsPerFrame(state));
}

void Threads(benchmark::internal::Benchmark* b) {
  b->Arg(1)->Arg(2)->ArgName("threads")->UseRealTime()->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_BareEmbree)->Apply(Threads);
BENCHMARK(BM_BareEmbreePackets)->Apply(Threads);
BENCHMARK(BM_RenderOnly)->Apply(Threads);
BENCHMARK(BM_FullFrame)->Apply(Threads);
BENCHMARK(BM_Pipeline)->Apply(Threads);
BENCHMARK_CAPTURE(BM_PipelinePart, sensor_apply, 0)->Arg(1)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PipelinePart, png8, 1)->Arg(1)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PipelinePart, png16, 2)->Arg(1)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PipelinePart, exr_with_t_true, 3)->Arg(1)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PipelinePart, visible_persons, 4)->Arg(1)->UseRealTime()->Unit(benchmark::kMillisecond);

void PrintSummary() {
  const Setup& s = Shared();
  const auto get = [&](const std::string& key) {
    const auto it = s.seconds_per_frame.find(key);
    return it == s.seconds_per_frame.end() ? 0.0 : it->second;
  };
  std::printf("\nSummary of this run (wall time per frame, %d poses along the route):\n", kPoses);
  for (const char* t : {"1", "2"}) {
    const double bare = get(std::string("bare/") + t);
    if (bare <= 0) continue;
    std::printf("  %s thread(s): bare Embree %.2f ms; render %.2f ms (%.2fx); render+sensor %.2f ms "
                "(%.2fx, target <= 2x); pipeline %.2f ms (%.2fx)\n",
                t, 1e3 * bare, 1e3 * get(std::string("render/") + t),
                get(std::string("render/") + t) / bare, 1e3 * get(std::string("full/") + t),
                get(std::string("full/") + t) / bare, 1e3 * get(std::string("pipeline/") + t),
                get(std::string("pipeline/") + t) / bare);
  }
  const double pipeline2 = get("pipeline/2");
  if (pipeline2 > 0) {
    std::printf("  2 threads: %.1f frames/s (pipeline), %.1f frames/s (render+sensor); "
                "%d frames projected %.0f s (without disk writes)\n",
                1.0 / pipeline2, 1.0 / get("full/2"), s.scene.frames, s.scene.frames * pipeline2);
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
