// hoilcd run [SCENE]: render a scene (or reuse its cached dataset), benchmark it, report.
#include "hoilcd/bench/pipeline/run.h"

#include <chrono>
#include <cstdio>
#include <memory>

#include "command.h"
#include "hoilcd/bench/report/gate.h"
#include "hoilcd/sim/assets/data_dir.h"
#include "shared.h"

namespace hoilcd {
namespace {

struct RunArgs {
  SceneArgs scene;
  BenchArgs bench;
  RunOptions run;
  GateArgs gate;
};

int RunCommand(const RunArgs& args) {
  SceneArgs a = args.scene;
  if (a.path.empty()) a.path = DataDir() + "/scenes/paper_room.json";
  const Scene scene = LoadSceneArgs(a);
  const nlohmann::json baseline = ReadBaseline(args.gate);
  RunOptions run = args.run;
  run.cancel = CancelOnInterrupt();
  const auto start = std::chrono::steady_clock::now();
  const RunOutcome outcome = RunScene(scene, ResolveBench(args.bench, run.threads), run);
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  PrintWarnings(outcome.warnings);
  PrintOutcome(outcome.result, outcome.report_dir);
  const ReportTiming& t = outcome.timing;
  std::string calibration;
  if (!outcome.calibration_dir.empty()) {
    char text[160];
    std::snprintf(text, sizeof(text), "; the SLAM calibration beside them, %.1f s (dataset %s, thresholds %s)",
                  t.calibration_s, t.calibration_render_cached ? "cached" : "rendered",
                  t.calibration_bench_cached ? "cached" : "benched");
    calibration = text;
  }
  std::printf("end to end: %.1f s: render %.1f s%s, then bench %.1f s and the report%s (dataset %s)\n", wall_s,
              t.render_s, t.render_cached ? " (cached)" : "", t.bench_s, calibration.c_str(),
              outcome.dataset_dir.c_str());
  return ApplyGate(args.gate, baseline, ReadReportJson(outcome.report_dir + "/report.json"));
}

}  // namespace

Command AddRunCommand(CLI::App* app) {
  auto args = std::make_shared<RunArgs>();
  args->bench.options.slam = true;  // hoilcd run reports the SLAM consequence by default
  CLI::App* cmd = app->add_subcommand("run", "render a scene (or reuse its cached dataset), benchmark it, report");
  AddSceneFlags(cmd, &args->scene, false);
  cmd->add_option("--cache", args->run.cache_dir, "folder of cached datasets and reports");
  cmd->add_option("-o,--output", args->run.report_dir, "report folder (default CACHE/<scene>-<hash>/report)");
  AddThreadsFlag(cmd, &args->run.threads);
  AddBenchFlags(cmd, &args->bench);
  AddGateFlags(cmd, &args->gate);
  return {cmd, [args] { return RunCommand(*args); }};
}

}  // namespace hoilcd
