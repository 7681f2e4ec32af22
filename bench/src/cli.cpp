#include "hoilcd/bench/cli.h"

#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>

#include "hoilcd/bench/coco_export.h"
#include "hoilcd/bench/diagnosis.h"
#include "hoilcd/bench/evaluate.h"
#include "hoilcd/bench/gate.h"
#include "hoilcd/bench/inspect.h"
#include "hoilcd/bench/mot_export.h"
#include "hoilcd/bench/method_params.h"
#include "hoilcd/bench/methods.h"
#include "hoilcd/bench/report.h"
#include "hoilcd/bench/run.h"
#include "hoilcd/bench/runner.h"
#include "hoilcd/bench/sweep.h"
#include "hoilcd/bench/sweep_summary.h"
#include "hoilcd/core/dataset.h"
#include "hoilcd/core/error.h"
#include "hoilcd/core/parallel.h"
#include "hoilcd/core/progress.h"
#include "hoilcd/sim/data_dir.h"
#include "hoilcd/sim/scene.h"
#include "hoilcd/sim/scene_options.h"
#include "hoilcd/sim/sequence.h"

namespace hoilcd {
namespace {

constexpr int kMaxThreadsFlag = 1024;  // --threads accepts this much (ParallelFor clamps to kMaxThreads)

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
  for (const std::string& warning : r.warnings) std::fprintf(stderr, "warning: %s\n", warning.c_str());
  std::printf("rendered %d frames (%d kept from an earlier run) into %s in %.1f s (%.1f frames/s)\n",
              r.frames_rendered, r.frames_reused, o.output_dir.c_str(), r.seconds,
              r.seconds > 0 ? r.frames_rendered / r.seconds : 0.0);
  // The encoder runs on a writer thread while later frames render: its time is not all added.
  std::printf("thermal.mp4: %.2f s of work, %.1f %% of the render's wall time (its encoding runs beside the rendering)\n",
              r.video_seconds, r.seconds > 0 ? 100.0 * r.video_seconds / r.seconds : 0.0);
  return 0;
}

// Flags shared by bench, run and sweep.
struct BenchArgs {
  std::string methods;
  BenchOptions options;
};

// Flags of the evaluation protocol (bench, run, sweep, evaluate).
void AddProtocolFlags(CLI::App* cmd, ProtocolOptions* protocol) {
  cmd->add_option("--protocol", protocol->protocol, "laps (database = first lap) or revisit")
      ->check(CLI::IsMember({"laps", "revisit"}));
  cmd->add_option("--radius", protocol->radius_m, "true-match radius, m (paper: 0.2)")->check(CLI::PositiveNumber);
  cmd->add_option("--exclusion-window", protocol->exclusion_window_s,
                  "frames this close in time to a query are not in its database, s")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--ground-truth", protocol->ground_truth,
                  "whose positions label true matches: odometry (the paper's) or true (the true poses)")
      ->check(CLI::IsMember({"odometry", "true"}));
  cmd->add_option("--heading-tolerance", protocol->heading_tolerance_deg,
                  "max heading difference of a true match, deg (negative: off)");
}

void AddBenchFlags(CLI::App* cmd, BenchArgs* args) {
  cmd->add_option("--methods", args->methods,
                  "comma-separated methods, or 'paper' / 'all' (default: all; see the report)");
  AddProtocolFlags(cmd, &args->options.protocol);
  cmd->add_option("--param", args->options.params,
                  "a parameter of one method or front end, e.g. slcd.ransac_trials=50, fusion.k=60, "
                  "persons.threshold_c=27 (repeatable; hoilcd params lists them)")
      ->type_name("NAME=VALUE");
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

// The CI gate's flags (bench, run, evaluate).
struct GateArgs {
  std::string baseline;
  double max_drop = 0;
  std::string junit;
};

void AddGateFlags(CLI::App* cmd, GateArgs* args) {
  CLI::Option* baseline = cmd->add_option("--baseline", args->baseline,
                  "earlier report.json: exit 3 when a headline metric (MRR, R@1) of a method in both dropped by "
                  "more than --max-drop");
  cmd->add_option("--max-drop", args->max_drop, "largest allowed drop of MRR or R@1 against --baseline (default 0)")
      ->check(CLI::NonNegativeNumber)
      ->needs(baseline);
  cmd->add_option("--junit", args->junit, "write JUnit XML here (one test case per method)");
}

// Compares `report` with the baseline and writes JUnit XML, as asked; the exit code (0, or 3 on
// any regression).
int ApplyGate(const GateArgs& args, const nlohmann::json& report) {
  std::vector<Regression> regressions;
  if (!args.baseline.empty()) {
    const nlohmann::json baseline = ReadReportJson(args.baseline);
    for (const std::string& m : MethodsOnlyInBaseline(baseline, report)) {
      std::printf("baseline: method %s is not in this run (not compared)\n", m.c_str());
    }
    regressions = CompareToBaseline(baseline, report, args.max_drop);
    for (const Regression& r : regressions) std::printf("%s\n", r.ToString(args.max_drop).c_str());
    if (regressions.empty()) std::printf("baseline %s: no headline metric dropped by more than %g\n", args.baseline.c_str(), args.max_drop);
  }
  if (!args.junit.empty()) WriteFileAtomic(args.junit, JUnitXml(report, regressions, args.max_drop));
  return regressions.empty() ? 0 : 3;
}

BenchOptions ResolveBench(const BenchArgs& args, int threads) {
  BenchOptions o = args.options;
  o.methods = args.methods.empty() ? DefaultMethods() : ParseMethodList(args.methods);
  o.threads = threads;
  CheckParams(o.params, o.methods);
  if (const std::string problem = o.Check(); !problem.empty()) throw InputError("bench options", problem);
  return o;
}

void PrintOutcome(const BenchResult& result, const std::string& report_dir) {
  std::printf("%s", FormatResultTable(result).c_str());
  std::printf("%s\n", PaperFindingSummary(result).c_str());
  std::printf("report: %s/report.md\n", report_dir.c_str());
}

int RunBenchCommand(const std::string& dir, const BenchArgs& args, const std::string& report_dir, int threads,
                    const std::string& dump_scores, const GateArgs& gate) {
  const Dataset dataset = Dataset::Open(dir, Verify::kOnRead, threads);
  for (const std::string& warning : dataset.warnings()) std::fprintf(stderr, "warning: %s\n", warning.c_str());
  const BenchOptions options = ResolveBench(args, threads);
  if (!gate.baseline.empty()) ReadReportJson(gate.baseline);  // a bad baseline fails before the work
  const std::string out = report_dir.empty() ? dir + "/report" : report_dir;
  ReportTiming timing;
  const BenchResult result = BenchAndWriteReport(dataset, options, &timing, out);
  if (!dump_scores.empty()) {
    for (const MethodRun& run : result.runs) {
      WriteFileAtomic(dump_scores + "/" + run.name + ".csv", ScoresToCsv(result.queries, run.scores));
    }
  }
  PrintOutcome(result, out);
  return ApplyGate(gate, ReadReportJson(out + "/report.json"));
}

int RunEvaluateCommand(const std::string& dir, const std::string& scores_path, std::string name,
                       const ProtocolOptions& protocol, const std::string& output, const GateArgs& gate) {
  const Dataset dataset = Dataset::Open(dir, Verify::kOnRead);
  for (const std::string& warning : dataset.warnings()) std::fprintf(stderr, "warning: %s\n", warning.c_str());
  if (!gate.baseline.empty()) ReadReportJson(gate.baseline);
  if (name.empty()) name = std::filesystem::path(scores_path).stem().string();
  if (name.empty()) throw InputError("--name", "a method name (the scores file name has none)");
  const MethodReport report = Evaluate(dataset, ReadScoresFile(scores_path, dataset.num_frames()), name, protocol);
  const nlohmann::json json = EvaluateReportJson(dataset, protocol, report, "scores from " + scores_path);
  const MethodMetrics& m = report.metrics;
  std::printf("%s (%s ground truth): MRR %.4f, R@1 %.4f, R@5 %.4f, PR-AUC %.4f; %d queries scored, %d skipped\n",
              name.c_str(), protocol.ground_truth.c_str(), m.mrr, m.recall_at_1, m.recall_at_5, m.pr_auc,
              m.queries_scored, m.queries_skipped);
  if (!output.empty()) {
    WriteFileAtomic(output, json.dump(2) + "\n");
    std::printf("report: %s\n", output.c_str());
  }
  return ApplyGate(gate, json);
}

int RunRunCommand(const SceneArgs& scene_args, const BenchArgs& args, RunOptions run, const GateArgs& gate) {
  SceneArgs a = scene_args;
  if (a.path.empty()) a.path = DataDir() + "/scenes/paper_room.json";
  const Scene scene = LoadSceneArgs(a);
  if (!gate.baseline.empty()) ReadReportJson(gate.baseline);  // a bad baseline fails before the work
  std::signal(SIGINT, OnInterrupt);
  run.cancel = &g_interrupted;
  const auto start = std::chrono::steady_clock::now();
  const RunOutcome outcome = RunScene(scene, ResolveBench(args, run.threads), run);
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (const std::string& warning : outcome.warnings) std::fprintf(stderr, "warning: %s\n", warning.c_str());
  PrintOutcome(outcome.result, outcome.report_dir);
  const ReportTiming& t = outcome.timing;
  std::string calibration;
  if (!outcome.calibration_dir.empty()) {
    char text[160];
    std::snprintf(text, sizeof(text), "; the SLAM calibration beside them, %.1f s (dataset %s, thresholds %s)", t.calibration_s,
                  t.calibration_render_cached ? "cached" : "rendered",
                  t.calibration_bench_cached ? "cached" : "benched");
    calibration = text;
  }
  std::printf("end to end: %.1f s: render %.1f s%s, then bench %.1f s and the report%s (dataset %s)\n", wall_s,
              t.render_s, t.render_cached ? " (cached)" : "", t.bench_s, calibration.c_str(),
              outcome.dataset_dir.c_str());
  return ApplyGate(gate, ReadReportJson(outcome.report_dir + "/report.json"));
}

int RunInspectCommand(const std::string& dir, const ProtocolOptions& protocol, bool json, const std::string& output) {
  const Dataset dataset = Dataset::Open(dir, Verify::kNothing);  // inspect looks at what is there
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
  KeepOpenCvOnCallingThread();  // every command's loops run on its --threads
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
      ->check(CLI::Range(0, kMaxThreadsFlag));
  render->add_option("--outputs", render_options.outputs,
                     "comma-separated outputs to write: thermal, radiometric, exr, video, persons (default: all; "
                     "the manifest lists them, and hoilcd bench needs thermal)");

  std::string bench_dir, bench_report;
  int bench_threads = 0;
  BenchArgs bench_args;
  CLI::App* bench = app.add_subcommand("bench", "evaluate loop-closure methods on a dataset folder");
  bench->add_option("dataset", bench_dir, "dataset folder written by hoilcd render")->required();
  bench->add_option("-o,--output", bench_report, "report folder (default DATASET/report)");
  bench->add_option("--threads", bench_threads, "worker threads (0: every core)")->check(CLI::Range(0, kMaxThreadsFlag));
  std::string dump_scores;
  bench->add_option("--dump-scores", dump_scores,
                    "write each method's scores as DIR/<method>.csv (query,reference,score), for hoilcd evaluate")
      ->type_name("DIR");
  AddBenchFlags(bench, &bench_args);
  GateArgs bench_gate;
  AddGateFlags(bench, &bench_gate);

  SceneArgs run_scene;
  BenchArgs run_args;
  run_args.options.slam = true;  // hoilcd run reports the SLAM consequence by default
  RunOptions run_options;
  CLI::App* run = app.add_subcommand("run", "render a scene (or reuse its cached dataset), benchmark it, report");
  AddSceneFlags(run, &run_scene, false);
  run->add_option("--cache", run_options.cache_dir, "folder of cached datasets and reports");
  run->add_option("-o,--output", run_options.report_dir, "report folder (default CACHE/<scene>-<hash>/report)");
  run->add_option("--threads", run_options.threads, "worker threads (0: every core)")->check(CLI::Range(0, kMaxThreadsFlag));
  AddBenchFlags(run, &run_args);
  GateArgs run_gate;
  AddGateFlags(run, &run_gate);

  std::string evaluate_dir, evaluate_scores, evaluate_name, evaluate_output;
  ProtocolOptions evaluate_protocol;
  GateArgs evaluate_gate;
  CLI::App* evaluate = app.add_subcommand(
      "evaluate", "apply the benchmark's protocol, labels and metrics to scores of a method hoilcd did not run");
  evaluate->add_option("dataset", evaluate_dir, "dataset folder written by hoilcd render")->required();
  evaluate->add_option("--scores", evaluate_scores,
                       "CSV with header query,reference,score (frame indices; pairs left out are unscored) or "
                       ".npy dense frames x frames float32/float64 matrix (NaN = unscored)")
      ->required();
  evaluate->add_option("--name", evaluate_name, "method name in the report (default: the scores file's name)");
  evaluate->add_option("-o,--output", evaluate_output, "write a report.json of this method here");
  AddProtocolFlags(evaluate, &evaluate_protocol);
  AddGateFlags(evaluate, &evaluate_gate);

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
  sweep->add_option("--threads", sweep_args.run.threads, "worker threads (0: every core)")->check(CLI::Range(0, kMaxThreadsFlag));
  AddBenchFlags(sweep, &sweep_bench);

  std::string coco_dataset, coco_output;
  CLI::App* coco = app.add_subcommand("export-coco", "the dataset's person keypoints as COCO keypoints JSON");
  coco->add_option("dataset", coco_dataset, "dataset folder written by hoilcd render")->required();
  coco->add_option("-o,--output", coco_output, "folder for person_keypoints.json")->required();

  CLI::App* params = app.add_subcommand("params", "list the --param NAMEs of every method and front end");

  std::string mot_dataset, mot_output;
  CLI::App* mot = app.add_subcommand(
      "export-mot", "ground-truth person boxes and the DLCD front end's tracks in MOTChallenge format (TrackEval)");
  mot->add_option("dataset", mot_dataset, "dataset folder written by hoilcd render")->required();
  mot->add_option("-o,--output", mot_output, "folder for gt/ and trackers/ (TrackEval's GT_FOLDER/TRACKERS_FOLDER)")
      ->required();
  int mot_threads = 0;
  mot->add_option("--threads", mot_threads, "worker threads (0: every core)")->check(CLI::Range(0, kMaxThreadsFlag));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  ProgressReporter::SetQuietByDefault(quiet);
  try {
    if (*validate) return RunValidate(validate_args);
    if (*render) return RunRender(render_args, render_options);
    if (*bench) return RunBenchCommand(bench_dir, bench_args, bench_report, bench_threads, dump_scores, bench_gate);
    if (*run) return RunRunCommand(run_scene, run_args, run_options, run_gate);
    if (*params) {
      std::printf("%s", FormatParams().c_str());
      return 0;
    }
    if (*evaluate) {
      return RunEvaluateCommand(evaluate_dir, evaluate_scores, evaluate_name, evaluate_protocol, evaluate_output,
                                evaluate_gate);
    }
    if (*mot) {
      const Dataset dataset = Dataset::Open(mot_dataset, Verify::kOnRead);
      BenchOptions options;
      options.threads = mot_threads;
      const MotExport e = ExportMot(dataset, options, mot_output);
      std::printf("wrote %s and %s (sequence %s; TrackEval: --BENCHMARK HOILCD --SPLIT_TO_EVAL train)\n",
                  e.ground_truth.c_str(), e.tracks.c_str(), e.sequence.c_str());
      return 0;
    }
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
