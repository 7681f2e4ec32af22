#include "hoilcd/bench/cli.h"

#include <CLI/CLI.hpp>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <exception>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>

#include "hoilcd/bench/diagnosis.h"
#include "hoilcd/bench/inspect.h"
#include "hoilcd/bench/coco_export.h"
#include "hoilcd/bench/methods.h"
#include "hoilcd/bench/report.h"
#include "hoilcd/bench/run.h"
#include "hoilcd/bench/runner.h"
#include "hoilcd/bench/sweep.h"
#include "hoilcd/bench/sweep_summary.h"
#include "hoilcd/core/dataset.h"
#include "hoilcd/core/error.h"
#include "hoilcd/core/progress.h"
#include "hoilcd/sim/scene.h"
#include "hoilcd/sim/scene_options.h"
#include "hoilcd/sim/sequence.h"

namespace hoilcd {
namespace {

constexpr int kMaxThreads = 1024;  // --threads cap: far above any machine, far below int overflow

std::atomic<bool> g_interrupted{false};

extern "C" void OnInterrupt(int) {
  g_interrupted = true;
  std::signal(SIGINT, SIG_DFL);  // a second Ctrl-C ends the process at once
}

// Flags shared by commands that read a scene.
struct SceneArgs {
  std::string path;
  std::vector<std::string> overrides;
  int64_t seed = -1;
};

Scene LoadSceneArgs(const SceneArgs& args) {
  std::vector<std::string> overrides = args.overrides;
  if (args.seed >= 0) overrides.push_back("seed=" + std::to_string(args.seed));
  return LoadScene(args.path, overrides);
}

int RunValidate(const SceneArgs& args) {
  // Print every problem, not only the first: validation is the point of this command.
  std::ifstream in(args.path);
  if (!in) throw InputError(args.path, "cannot open the scene file (does it exist and is it readable?)");
  const Scene scene = LoadSceneArgs(args);
  SensorOptionsFromScene(scene);  // the camera's cross-field checks (the schema checks each field)
  VideoOptionsFromScene(scene);   // frame rate and size that thermal.mp4 can carry
  std::printf("%s: valid scene '%s' (%d frames at %g Hz, %zu tables, hash %s)\n", args.path.c_str(),
              scene.name.c_str(), scene.frames, scene.frame_rate_hz, scene.tables.size(),
              scene.hash.c_str());
  return 0;
}

int RunRender(const SceneArgs& args, const SequenceOptions& options) {
  const Scene scene = LoadSceneArgs(args);
  std::signal(SIGINT, OnInterrupt);
  SequenceOptions o = options;
  o.cancel = &g_interrupted;
  const SequenceResult r = RenderSequence(scene, o);
  std::printf("rendered %d frames (%d kept from an earlier run) into %s in %.1f s (%.1f frames/s)\n",
              r.frames_rendered, r.frames_reused, o.output_dir.c_str(), r.seconds,
              r.seconds > 0 ? r.frames_rendered / r.seconds : 0.0);
  std::printf("of which thermal.mp4: %.2f s (%.1f %% of the render)\n", r.video_seconds,
              r.seconds > 0 ? 100.0 * r.video_seconds / r.seconds : 0.0);
  return 0;
}

// Flags shared by bench, run and sweep.
struct BenchArgs {
  std::string methods;
  BenchOptions options;
};

void AddBenchFlags(CLI::App* cmd, BenchArgs* args) {
  cmd->add_option("--methods", args->methods,
                  "comma-separated methods, or 'paper' / 'all' (default: all; see the report)");
  cmd->add_option("--protocol", args->options.protocol.protocol, "laps (database = first lap) or revisit")
      ->check(CLI::IsMember({"laps", "revisit"}));
  cmd->add_option("--radius", args->options.protocol.radius_m, "true-match radius, m (paper: 0.2)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--exclusion-window", args->options.protocol.exclusion_window_s,
                  "frames this close in time to a query are not in its database, s")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--ground-truth", args->options.protocol.ground_truth,
                  "whose positions label true matches: odometry (the paper's) or true (the true poses)")
      ->check(CLI::IsMember({"odometry", "true"}));
  cmd->add_option("--heading-tolerance", args->options.protocol.heading_tolerance_deg,
                  "max heading difference of a true match, deg (negative: off)");
  cmd->add_option("--detector", args->options.keypoints.detector, "SLCD keypoints: gftt, fast, orb, sift, akaze")
      ->check(CLI::IsMember({"gftt", "fast", "orb", "sift", "akaze"}));
  cmd->add_option("--rrf-k", args->options.rrf_k, "reciprocal rank fusion constant (paper: 0)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--slam,!--no-slam", args->options.slam,
                "each method's loops in a pose graph: ATE/RPE per back end (default: on in run, off in bench)");
  cmd->add_option("--slam-backend", args->options.slam_options.slam.graph.backend,
                  "headline pose-graph back end: plain, cauchy or dcs (all three are reported)")
      ->check(CLI::IsMember(PoseGraphBackends()));
  cmd->add_option("--loop-threshold", args->options.slam_options.slam.loop_threshold,
                  "accept a method's top-1 match as a loop when its score is at least this (default: the "
                  "threshold of 100 % precision on the calibration sequence)");
}

BenchOptions ResolveBench(const BenchArgs& args, int threads) {
  BenchOptions o = args.options;
  o.methods = args.methods.empty() ? DefaultMethods() : ParseMethodList(args.methods);
  o.threads = threads;
  if (const std::string problem = o.Check(); !problem.empty()) throw InputError("bench options", problem);
  return o;
}

void PrintOutcome(const BenchResult& result, const std::string& report_dir) {
  std::printf("%s", FormatResultTable(result).c_str());
  std::printf("%s\n", PaperFindingSummary(result).c_str());
  std::printf("report: %s/report.md\n", report_dir.c_str());
}

int RunBenchCommand(const std::string& dir, const BenchArgs& args, const std::string& report_dir, int threads) {
  const Dataset dataset = Dataset::Open(dir, /*verify_checksums=*/true);
  for (const std::string& warning : dataset.warnings()) std::fprintf(stderr, "warning: %s\n", warning.c_str());
  const BenchOptions options = ResolveBench(args, threads);
  const BenchResult result = RunBench(dataset, options);
  const std::string out = report_dir.empty() ? dir + "/report" : report_dir;
  ReportTiming timing;
  timing.bench_s = result.seconds;
  WriteReport(result, dataset, options, timing, out);
  PrintOutcome(result, out);
  return 0;
}

int RunRunCommand(const SceneArgs& scene_args, const BenchArgs& args, RunOptions run) {
  SceneArgs a = scene_args;
  if (a.path.empty()) a.path = std::string(HOILCD_SOURCE_DIR) + "/scenes/paper_room.json";
  const Scene scene = LoadSceneArgs(a);
  std::signal(SIGINT, OnInterrupt);
  run.cancel = &g_interrupted;
  const RunOutcome outcome = RunScene(scene, ResolveBench(args, run.threads), run);
  for (const std::string& warning : outcome.warnings) std::fprintf(stderr, "warning: %s\n", warning.c_str());
  PrintOutcome(outcome.result, outcome.report_dir);
  std::printf("end to end: %.1f s = render %.1f s%s + bench %.1f s (dataset %s)\n",
              outcome.timing.render_s + outcome.timing.bench_s, outcome.timing.render_s,
              outcome.timing.render_cached ? " (cached)" : "", outcome.timing.bench_s,
              outcome.dataset_dir.c_str());
  return 0;
}

int RunInspectCommand(const std::string& dir, const ProtocolOptions& protocol, bool json, const std::string& output) {
  const Dataset dataset = Dataset::Open(dir, /*verify_checksums=*/false);
  const InspectReport report = InspectDataset(dataset, protocol);
  const std::string json_text = report.ToJson().dump(2) + "\n";
  if (!output.empty()) WriteFileAtomic(output, json_text);
  std::printf("%s", json ? json_text.c_str() : ("dataset " + dir + "\n" + report.ToText()).c_str());
  return 0;
}

// Flags of `hoilcd sweep`.
struct SweepArgs {
  std::string scene;
  std::vector<std::string> sets;
  int seeds = 1;
  std::string shard;
  std::vector<std::string> merge;
  std::string output;
  RunOptions run;
};

void PrintSweepSummary(const SweepSummary& summary, const std::string& out) {
  std::printf("%s", summary.FormatTable().c_str());
  std::printf("summary: %s/summary.md (and summary.csv, plot_*.png)\n", out.c_str());
}

int RunSweepCommand(const SweepArgs& args, const BenchArgs& bench_args) {
  if (!args.merge.empty()) {
    if (!args.shard.empty()) throw InputError("--shard", "cannot be combined with --merge (a merge reads every shard)");
    std::optional<SweepPlan> expected;
    if (!args.scene.empty()) {
      expected = MakeSweepPlan(args.scene, args.sets, args.seeds, ResolveBench(bench_args, args.run.threads));
    } else if (!args.sets.empty()) {
      throw InputError("--set", "with --merge, --set is only checked against the shards when SCENE is given too");
    }
    const SweepSummary summary = MergeSweep(args.merge, expected ? &*expected : nullptr);
    WriteSweepSummary(summary, args.output);
    PrintSweepSummary(summary, args.output);
    return 0;
  }
  if (args.scene.empty()) throw InputError("sweep", "a SCENE file is needed (or --merge DIR... to combine shard outputs)");
  SweepOptions options;
  options.output_dir = args.output;
  options.run = args.run;
  if (!args.shard.empty()) options.shard = ParseSweepShard(args.shard);
  const BenchOptions bench = ResolveBench(bench_args, args.run.threads);
  const SweepPlan plan = MakeSweepPlan(args.scene, args.sets, args.seeds, bench);
  std::signal(SIGINT, OnInterrupt);
  options.run.cancel = &g_interrupted;
  std::printf("sweep of %s: %zu runs (%zu combinations x %d seeds)", plan.scene_name.c_str(), plan.Runs().size(),
              plan.Combinations().size(), plan.seeds);
  if (options.shard.count > 1) std::printf(", shard %d/%d does %zu", options.shard.index, options.shard.count, plan.ShardRuns(options.shard).size());
  std::printf("\n");
  RunSweep(plan, bench, options, [](int position, int total, const SweepRunSpec& run, bool kept) {
    std::printf("run %d/%d: %s%s\n", position, total, run.Name().c_str(), kept ? " (kept from an earlier sweep)" : "");
    std::fflush(stdout);
  });
  if (options.shard.count > 1) {
    std::printf("shard %d/%d done in %s; when every shard is done: hoilcd sweep --merge DIR... -o OUT\n",
                options.shard.index, options.shard.count, args.output.c_str());
    return 0;
  }
  const SweepSummary summary = MergeSweep({args.output}, &plan);
  WriteSweepSummary(summary, args.output);
  PrintSweepSummary(summary, args.output);
  return 0;
}

void AddSceneFlags(CLI::App* cmd, SceneArgs* args, bool scene_required) {
  auto* opt = cmd->add_option("scene", args->path, "scene file (JSON, see scenes/scene.schema.json)");
  if (scene_required) opt->required();
  cmd->add_option("--set", args->overrides,
                  "override a scene value by its path, e.g. --set crowd.people_per_table=2 (repeatable)")
      ->type_name("KEY=VALUE");
  cmd->add_option("--seed", args->seed, "override the scene's seed")->check(CLI::NonNegativeNumber);
}

}  // namespace

int RunCommandLine(int argc, char** argv) {
  CLI::App app{"hoilcd: synthetic thermal scene simulator and loop-closure benchmark"};
  app.set_version_flag("--version", HOILCD_VERSION);
  app.require_subcommand(1);
  bool quiet = false;
  app.add_flag("-q,--quiet", quiet, "no progress bars");

  SceneArgs validate_args;
  CLI::App* validate = app.add_subcommand("validate", "check a scene file; print every problem with its JSON path");
  AddSceneFlags(validate, &validate_args, true);

  SceneArgs render_args;
  SequenceOptions render_options;
  CLI::App* render = app.add_subcommand("render", "render a scene's sequence into a dataset folder");
  AddSceneFlags(render, &render_args, true);
  render->add_option("-o,--output", render_options.output_dir, "dataset folder (resumed if it holds an interrupted render of the same scene)")
      ->required();
  render->add_option("--frames", render_options.frames, "render only the first N frames (0: all)")
      ->check(CLI::NonNegativeNumber);
  render->add_option("--threads", render_options.threads, "worker threads (0: every core)")
      ->check(CLI::Range(0, kMaxThreads));

  std::string bench_dir, bench_report;
  int bench_threads = 0;
  BenchArgs bench_args;
  CLI::App* bench = app.add_subcommand("bench", "evaluate loop-closure methods on a dataset folder");
  bench->add_option("dataset", bench_dir, "dataset folder written by hoilcd render")->required();
  bench->add_option("-o,--output", bench_report, "report folder (default DATASET/report)");
  bench->add_option("--threads", bench_threads, "worker threads (0: every core)")->check(CLI::Range(0, kMaxThreads));
  AddBenchFlags(bench, &bench_args);

  SceneArgs run_scene;
  BenchArgs run_args;
  run_args.options.slam = true;  // hoilcd run reports the SLAM consequence by default
  RunOptions run_options;
  CLI::App* run = app.add_subcommand("run", "render a scene (or reuse its cached dataset), benchmark it, report");
  AddSceneFlags(run, &run_scene, false);
  run->add_option("--cache", run_options.cache_dir, "folder of cached datasets and reports");
  run->add_option("-o,--output", run_options.report_dir, "report folder (default CACHE/<scene>-<hash>/report)");
  run->add_option("--threads", run_options.threads, "worker threads (0: every core)")->check(CLI::Range(0, kMaxThreads));
  AddBenchFlags(run, &run_args);

  std::string inspect_dir, inspect_output;
  bool inspect_json = false;
  ProtocolOptions inspect_protocol;
  CLI::App* inspect = app.add_subcommand(
      "inspect", "what to check before trusting a dataset: laps, lap-to-lap path difference, odometry drift, "
                 "camera jitter, people in view, occlusion, odometric vs true ground truth");
  inspect->add_option("dataset", inspect_dir, "dataset folder written by hoilcd render")->required();
  inspect->add_flag("--json", inspect_json, "print the figures as JSON instead of text");
  inspect->add_option("-o,--output", inspect_output, "also write the figures as JSON to this file");
  inspect->add_option("--protocol", inspect_protocol.protocol, "laps (database = first lap) or revisit")
      ->check(CLI::IsMember({"laps", "revisit"}));
  inspect->add_option("--radius", inspect_protocol.radius_m, "true-match radius, m (paper: 0.2)")
      ->check(CLI::PositiveNumber);

  SweepArgs sweep_args;
  BenchArgs sweep_bench;
  CLI::App* sweep = app.add_subcommand(
      "sweep", "run a scene over the cross product of --set values x seeds; summary table and plots");
  sweep->footer(
      "Every run's report is kept; the summary gives mean, std, min and max over seeds and a plot of\n"
      "each metric against each swept value.\n"
      "--shard I/N runs only every N-th run starting at I (0 <= I < N) of the sorted run list, for\n"
      "job arrays; OUT/sweep.json marks the shard. --merge DIR... -o OUT combines shard outputs\n"
      "(nothing is rendered) and fails naming any run that is missing or present twice. With\n"
      "SCENE and the shards' --set/--seeds/bench flags, a merge also checks the shards ran exactly\n"
      "that sweep; without SCENE, the sweep is read from the shards (they must agree).");
  sweep->add_option("scene", sweep_args.scene, "scene file (JSON); optional with --merge");
  sweep->add_option("--set", sweep_args.sets,
                    "KEY=V1,V2,...: values to sweep (split on top-level commas, so [1,2] is one value); repeatable, "
                    "the cross product is run")
      ->type_name("KEY=V1,V2")
      ->allow_extra_args(false);
  sweep->add_option("--seeds", sweep_args.seeds, "run every combination with seeds 1..N")->check(CLI::PositiveNumber);
  sweep->add_option("--cache", sweep_args.run.cache_dir, "folder of cached datasets (shared by every run and shard)");
  sweep->add_option("-o,--output", sweep_args.output, "sweep folder: runs/<KEY=V,...,seed=S>/, summary.csv, summary.md, plots")
      ->required();
  sweep->add_option("--shard", sweep_args.shard, "run only part I of N (0-based, e.g. $SLURM_ARRAY_TASK_ID/4)")
      ->type_name("I/N");
  sweep->add_option("--merge", sweep_args.merge, "combine these sweep output folders into OUT")->type_name("DIR...");
  sweep->add_option("--threads", sweep_args.run.threads, "worker threads (0: every core)")->check(CLI::Range(0, kMaxThreads));
  AddBenchFlags(sweep, &sweep_bench);

  std::string coco_dataset, coco_output;
  CLI::App* coco = app.add_subcommand("export-coco", "the dataset's person keypoints as COCO keypoints JSON");
  coco->add_option("dataset", coco_dataset, "dataset folder written by hoilcd render")->required();
  coco->add_option("-o,--output", coco_output, "folder for person_keypoints.json")->required();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  ProgressReporter::SetQuietByDefault(quiet);
  try {
    if (*validate) return RunValidate(validate_args);
    if (*render) return RunRender(render_args, render_options);
    if (*bench) return RunBenchCommand(bench_dir, bench_args, bench_report, bench_threads);
    if (*run) return RunRunCommand(run_scene, run_args, run_options);
    if (*sweep) return RunSweepCommand(sweep_args, sweep_bench);
    if (*inspect) return RunInspectCommand(inspect_dir, inspect_protocol, inspect_json, inspect_output);
    if (*coco) {
      std::printf("wrote %s\n", ExportCoco(coco_dataset, coco_output).c_str());
      return 0;
    }
  } catch (const InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  } catch (const RenderInterrupted& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 130;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "internal error: %s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace hoilcd
