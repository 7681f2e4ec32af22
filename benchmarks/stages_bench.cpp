// Frame rate of every stage of making a dataset, in one run (issue 16): bare Embree packet
// casting of the renderer's primary rays, FrameRenderer::Render, render + SensorModel::Apply, the
// whole frame before encoding (World::SetTime, render, sensor, T_true, visible-person ground
// truth) and writing the dataset with all outputs (RenderSequence: PNGs, EXR, thermal.mp4,
// persons.json, manifest, fsyncs). Each stage is given in frames per second and as a fraction of
// bare packet casting. The first four run per frame, back to back, on the scene's first N frames
// so load from other processes hits them alike; writing is RenderSequence of those N frames into
// a fresh folder, less RenderSequence of 1 frame (set-up: assets, BVH, the robot's whole route).
// Rounds alternate the two parts. Options after Google Benchmark's own:
//   build/bin/stages_bench [--frames=N (200)] [--threads=N (2)] [--rounds=N (2)]
//                            [--scene=FILE (paper_room)] [--out=DIR (system temp folder)]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>
#include <unistd.h>

#include "bare_packets.h"
#include "hoilcd/core/util/allocator.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/sim/assets/data_dir.h"
#include "hoilcd/sim/output/sequence.h"
#include "hoilcd/sim/render/renderer.h"
#include "hoilcd/sim/render/visibility.h"
#include "hoilcd/sim/scene/scene.h"
#include "hoilcd/sim/scene/scene_options.h"
#include "hoilcd/sim/sensor/sensor.h"

namespace hoilcd {
namespace {

struct Settings {
  int frames = 200;  // frames of the scene's route timed per round
  int threads = 2;   // threads of every stage (RenderSequence's --threads)
  int rounds = 2;    // rounds of (per-frame stages, dataset writing)
  std::string scene = DataDir() + "/scenes/paper_room.json";
  std::string out = std::filesystem::temp_directory_path().string();  // writing goes under here
};

Settings& TheSettings() {
  static Settings settings;
  return settings;
}

enum Stage { kBarePackets, kRender, kRenderSensor, kWholeFrame, kWriting, kStages };
const char* const kStageNames[kStages] = {"bare Embree packets (rtcIntersect16)", "render", "render + sensor",
                                          "whole frame (SetTime, render, sensor, T_true, persons)",
                                          "dataset writing, all outputs (RenderSequence)"};
const char* const kStageKeys[kStages] = {"fps_bare_packets", "fps_render", "fps_render_sensor", "fps_whole_frame",
                                         "fps_writing"};

// Wall and process CPU seconds of one stage, summed over frames.
struct Timer {
  double wall_s = 0, cpu_s = 0;
  int64_t frames = 0;
};

template <typename Fn>
void Time(Timer* timer, int64_t frames, Fn&& fn) {
  const auto wall = std::chrono::steady_clock::now();
  const std::clock_t cpu = std::clock();
  fn();
  timer->wall_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count();
  timer->cpu_s += static_cast<double>(std::clock() - cpu) / CLOCKS_PER_SEC;
  timer->frames += frames;
}

// RenderSequence of the scene's first `frames` frames into a new folder under settings.out;
// returns its wall time (the folder is removed).
double WriteDataset(const Scene& scene, int frames, const std::string& name) {
  const Settings& settings = TheSettings();
  SequenceOptions options;
  options.output_dir = settings.out + "/hoilcd-stages-" + std::to_string(getpid()) + "-" + name;
  options.frames = frames;
  options.threads = settings.threads;
  std::filesystem::remove_all(options.output_dir);
  const double seconds = RenderSequence(scene, options).seconds;
  std::filesystem::remove_all(options.output_dir);
  return seconds;
}

Timer g_timers[kStages];

void BM_Stages(benchmark::State& state) {
  const Settings& settings = TheSettings();
  Scene scene = LoadScene(settings.scene);
  if (settings.frames < 2 || settings.frames > scene.frames) {
    state.SkipWithError("--frames must be in [2, the scene's frame count]");
    return;
  }
  // As RenderSequence runs every stage: freed frame buffers kept for reuse, not returned to the
  // kernel and faulted in again (before, only the stages after the first writing ran so).
  KeepFreedMemoryForReuse();
  const BandRadianceTable table;
  World world(scene, table);
  const CameraIntrinsics intrinsics = IntrinsicsFromScene(scene);
  const RobotRun run = SimulateSceneRobot(scene, world.obstacles());
  std::vector<Eigen::Vector3f> cam_directions;
  for (int y = 0; y < intrinsics.height; ++y) {
    for (int x = 0; x < intrinsics.width; ++x) {
      cam_directions.push_back(intrinsics.Unproject(x, y).cast<float>().normalized());
    }
  }
  const FrameRenderer renderer(world, intrinsics, RenderOptionsFromScene(scene, settings.threads));
  const SensorOptions sensor_options = SensorOptionsFromScene(scene);
  BareHits hits(static_cast<int>(cam_directions.size()));
  for (auto _ : state) {
    for (int round = 0; round < settings.rounds; ++round) {
      // Fresh sensors per round: the sensor's time constant and drift carry state frame to frame.
      SensorModel sensor(sensor_options, intrinsics.width, intrinsics.height, scene.frame_rate_hz, scene.seed, &table,
                         settings.threads);
      SensorModel whole_sensor(sensor_options, intrinsics.width, intrinsics.height, scene.frame_rate_hz, scene.seed,
                               &table, settings.threads);
      for (int f = 0; f < settings.frames; ++f) {
        const RobotSample& sample = run.samples[f];
        world.SetTime(sample.time_s);
        Time(&g_timers[kBarePackets], 1,
             [&] { CastBarePackets(world, intrinsics, cam_directions, sample.camera, settings.threads, &hits); });
        Time(&g_timers[kRender], 1, [&] { benchmark::DoNotOptimize(renderer.Render(sample.camera).radiance.data); });
        Time(&g_timers[kRenderSensor], 1,
             [&] { benchmark::DoNotOptimize(sensor.Apply(f, renderer.Render(sample.camera).radiance).data); });
        Time(&g_timers[kWholeFrame], 1, [&] {
          world.SetTime(sample.time_s);
          const FrameBuffers buffers = renderer.Render(sample.camera);
          benchmark::DoNotOptimize(whole_sensor.Apply(f, buffers.radiance).data);
          benchmark::DoNotOptimize(whole_sensor.IdealTemperature(buffers.radiance).data);
          benchmark::DoNotOptimize(
              VisiblePersons(world, intrinsics, sample.camera, buffers.instance, buffers.depth_m, settings.threads)
                  .data());
        });
      }
      // Writing: N frames less 1 frame, so set-up (assets, BVH, the route) cancels out.
      Timer one, many;
      Time(&one, 0, [&] { WriteDataset(scene, 1, "one"); });
      Time(&many, 0, [&] { WriteDataset(scene, settings.frames, "many"); });
      g_timers[kWriting].wall_s += many.wall_s - one.wall_s;
      g_timers[kWriting].cpu_s += many.cpu_s - one.cpu_s;
      g_timers[kWriting].frames += settings.frames - 1;
    }
  }
  for (int s = 0; s < kStages; ++s) {
    state.counters[kStageKeys[s]] = g_timers[s].frames / g_timers[s].wall_s;
  }
}

void PrintTable() {
  const Settings& settings = TheSettings();
  const Timer& bare = g_timers[kBarePackets];
  if (bare.frames == 0) return;
  const double bare_fps = bare.frames / bare.wall_s, bare_cpu_fps = bare.frames / bare.cpu_s;
  std::printf(
      "\nStages of one run: %s, first %d frames, %d thread(s), %d round(s); wall time (process CPU "
      "time of all threads in brackets)\n\n",
      settings.scene.c_str(), settings.frames, settings.threads, settings.rounds);
  std::printf("| stage | ms per frame | frames/s | of bare packets (wall) | of bare packets (CPU) |\n");
  std::printf("|---|---|---|---|---|\n");
  for (int s = 0; s < kStages; ++s) {
    const Timer& t = g_timers[s];
    const double fps = t.frames / t.wall_s, cpu_fps = t.frames / t.cpu_s;
    std::printf("| %s | %.2f [%.2f] | %.1f | %.1f %% | %.1f %% |\n", kStageNames[s], 1e3 * t.wall_s / t.frames,
                1e3 * t.cpu_s / t.frames, fps, 100.0 * fps / bare_fps, 100.0 * cpu_fps / bare_cpu_fps);
  }
  std::printf(
      "\nDataset writing: RenderSequence of %d frames less RenderSequence of 1 frame, into %s "
      "(removed after).\n",
      settings.frames, settings.out.c_str());
}

BENCHMARK(BM_Stages)->Iterations(1)->UseRealTime()->Unit(benchmark::kSecond);

// Our options (Google Benchmark has taken its own out of argv); false on an unknown one.
bool ParseSettings(int argc, char** argv) {
  Settings& s = TheSettings();
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto value = [&](const char* name) {
      const std::string prefix = std::string(name) + "=";
      return arg.rfind(prefix, 0) == 0 ? arg.substr(prefix.size()) : std::string();
    };
    try {
      if (!value("--frames").empty()) {
        s.frames = std::stoi(value("--frames"));
      } else if (!value("--threads").empty()) {
        s.threads = std::stoi(value("--threads"));
      } else if (!value("--rounds").empty()) {
        s.rounds = std::stoi(value("--rounds"));
      } else if (!value("--scene").empty()) {
        s.scene = value("--scene");
      } else if (!value("--out").empty()) {
        s.out = value("--out");
      } else {
        std::fprintf(stderr,
                     "stages_bench: unknown argument %s (--frames=N --threads=N --rounds=N "
                     "--scene=FILE --out=DIR)\n",
                     arg.c_str());
        return false;
      }
    } catch (const std::exception&) {
      std::fprintf(stderr, "stages_bench: %s: expected an integer\n", arg.c_str());
      return false;
    }
  }
  if (s.threads < 1 || s.rounds < 1) {
    std::fprintf(stderr, "stages_bench: --threads and --rounds must be positive\n");
    return false;
  }
  return true;
}

}  // namespace
}  // namespace hoilcd

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (!hoilcd::ParseSettings(argc, argv)) return 2;
  benchmark::RunSpecifiedBenchmarks();
  hoilcd::PrintTable();
  benchmark::Shutdown();
  return 0;
}
