// hoilcd sweep SCENE --set KEY=V1,V2 --seeds N -o OUT: a scene over the cross product of values
// and seeds, with a summary table and plots; --shard and --merge split it over machines.
#include "hoilcd/bench/pipeline/sweep.h"

#include <cstdio>
#include <memory>
#include <optional>

#include "command.h"
#include "hoilcd/bench/pipeline/sweep_summary.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/folder_lock.h"
#include "shared.h"

namespace hoilcd {
namespace {

struct SweepArgs {
  std::string scene;
  std::vector<std::string> sets;
  int seeds = 1;
  std::optional<std::string> shard;
  std::vector<std::string> merge;
  std::string output;
  RunOptions run;
  BenchArgs bench;
};

void PrintSweepSummary(const SweepSummary& summary, const std::string& out) {
  std::printf("%s", summary.FormatTable().c_str());
  std::printf("summary: %s/summary.md (and summary.csv, plot_*.png)\n", out.c_str());
  std::fflush(stdout);  // the warning follows the table, also where stdout and stderr share a log
  if (const std::string warning = summary.Warning(); !warning.empty()) PrintWarnings({warning});
}

int MergeCommand(const SweepArgs& args) {
  if (args.shard) throw InputError("--shard", "cannot be combined with --merge (a merge reads every shard)");
  const std::string renders_nothing = "not with --merge: a merge renders and benches nothing";
  for (const char* flag : {"--cache", "--drop-datasets", "--threads"})
    RefuseIfGiven(*args.bench.cmd, flag, renders_nothing);
  if (args.scene.empty()) {
    const std::string needs_scene =
        "with --merge, the sweep's flags are only checked against the shards when SCENE is given too";
    RefuseIfGiven(*args.bench.cmd, "--seeds", needs_scene);
    RefuseBenchFlags(args.bench, needs_scene);
  }
  std::optional<SweepPlan> expected;
  if (!args.scene.empty()) {
    expected = MakeSweepPlan(args.scene, args.sets, args.seeds, ResolveBench(args.bench, args.run.threads));
  } else if (!args.sets.empty()) {
    throw InputError("--set", "with --merge, --set is only checked against the shards when SCENE is given too");
  }
  CheckSweepSummaryFolder(args.output);
  const FolderLock lock(args.output, FolderLock::IfBusy::kRefuse);
  const SweepSummary summary = MergeSweep(args.merge, expected ? &*expected : nullptr);
  WriteSweepSummary(summary, args.output);
  PrintSweepSummary(summary, args.output);
  return 0;
}

int SweepCommand(const SweepArgs& args) {
  if (!args.merge.empty()) return MergeCommand(args);
  if (args.scene.empty())
    throw InputError("sweep", "a SCENE file is needed (or --merge DIR... to combine shard outputs)");
  SweepOptions options;
  options.output_dir = args.output;
  options.run = args.run;
  if (args.shard) options.shard = ParseShard(*args.shard);
  const BenchOptions bench = ResolveBench(args.bench, args.run.threads);
  const SweepPlan plan = MakeSweepPlan(args.scene, args.sets, args.seeds, bench);
  options.run.cancel = CancelOnInterrupt();
  std::printf("sweep of %s: %zu runs (%zu combinations x %d seeds)", plan.scene_name.c_str(), plan.Runs().size(),
              plan.Combinations().size(), plan.seeds);
  if (options.shard.count > 1)
    std::printf(", shard %d/%d does %zu", options.shard.index, options.shard.count,
                plan.ShardRuns(options.shard).size());
  std::printf("\n");
  // Held from the first run to the summary (RunSweep and WriteSweepSummary take it again): a second
  // sweep into this folder is refused by name.
  const FolderLock lock(args.output, FolderLock::IfBusy::kRefuse);
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

}  // namespace

Command AddSweepCommand(CLI::App* app) {
  auto args = std::make_shared<SweepArgs>();
  CLI::App* cmd = app->add_subcommand(
      "sweep", "run a scene over the cross product of --set values x seeds; summary table and plots");
  cmd->footer(
      "Every run's report is kept; the summary gives mean, std, min and max over seeds and a plot of\n"
      "each metric against each swept value.\n"
      "--shard I/N runs only every N-th run starting at I (0 <= I < N) of the sorted run list, for\n"
      "job arrays; OUT/sweep.json marks the shard. --merge DIR... -o OUT combines shard outputs\n"
      "(nothing is rendered) and fails naming any run that is missing or present twice. With\n"
      "SCENE and the shards' --set/--seeds/bench flags, a merge also checks the shards ran exactly\n"
      "that sweep; without SCENE, the sweep is read from the shards (they must agree).");
  cmd->add_option("scene", args->scene, "scene file (JSON); optional with --merge");
  cmd->add_option("--set", args->sets,
                  "KEY=V1,V2,...: values to sweep (split on top-level commas, so [1,2] is one value); repeatable, "
                  "the cross product is run")
      ->type_name("KEY=V1,V2")
      ->allow_extra_args(false);
  // Each seed is a full render and bench (about a minute): more than this is a typo, not a plan.
  constexpr double kMaxSeeds = 10000;
  cmd->add_option("--seeds", args->seeds, "run every combination with seeds 1..N")
      ->check(NumberIn(OptionRange::Closed(1, kMaxSeeds)));
  AddManyRunsCacheFlags(cmd, &args->run);
  cmd->add_option("-o,--output", args->output, "sweep folder: runs/<KEY=V,...,seed=S>/, summary.csv, summary.md, plots")
      ->required();
  AddShardFlag(cmd, &args->shard, "run only part I of N (0-based, e.g. $SLURM_ARRAY_TASK_ID/4)");
  cmd->add_option("--merge", args->merge, "combine these sweep output folders into OUT")->type_name("DIR...");
  AddThreadsFlag(cmd, &args->run.threads);
  AddBenchFlags(cmd, &args->bench);
  return {cmd, [args] { return SweepCommand(*args); }};
}

}  // namespace hoilcd
