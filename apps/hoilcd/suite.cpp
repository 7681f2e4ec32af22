// hoilcd suite SUITE -o OUT: every (sequence, seed) of a suite file rendered and benched, and a
// report of each method's mean over runs with its interval, ranks and paired wins; --shard and
// --merge split the runs over machines.
#include "hoilcd/bench/pipeline/suite.h"

#include <cstdio>
#include <memory>
#include <optional>

#include "command.h"
#include "hoilcd/bench/pipeline/suite_report.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/folder_lock.h"
#include "hoilcd/core/util/text.h"
#include "shared.h"

namespace hoilcd {
namespace {

struct SuiteArgs {
  std::string suite;
  std::string output;
  std::string split = "all";
  std::optional<std::string> shard;
  std::vector<std::string> merge;
  RunOptions run;
  BenchArgs bench;
};

// Writes and prints the report; 1 when a run failed, as the unsharded suite and the merge exit.
int WriteAndPrintReport(const SuiteSummary& summary, const std::string& out) {
  WriteSuiteReport(summary, out);
  for (const SuiteMethodSummary& m : summary.methods) {
    std::printf("%-16s MRR %s [%s, %s]  mean rank %s\n", m.method.c_str(), Fixed(m.mean_mrr, 3).c_str(),
                Fixed(m.mrr_interval.low, 3).c_str(), Fixed(m.mrr_interval.high, 3).c_str(),
                Fixed(m.mean_rank, 2).c_str());
  }
  for (const auto& [run, error] : summary.failed) std::fprintf(stderr, "failed: %s: %s\n", run.c_str(), error.c_str());
  std::printf("report: %s/suite_report.md (and suite_report.json)\n", out.c_str());
  if (!summary.failed.empty()) {
    std::fprintf(stderr, "error: %zu of %zu runs failed\n", summary.failed.size(),
                 summary.failed.size() + summary.runs.size());
    return 1;
  }
  return 0;
}

int MergeCommand(const SuiteArgs& args) {
  if (args.shard) throw InputError("--shard", "cannot be combined with --merge (a merge reads every shard)");
  const std::string runs_nothing = "not with --merge: a merge renders and benches nothing";
  for (const char* flag : {"--cache", "--drop-datasets", "--threads"})
    RefuseIfGiven(*args.bench.cmd, flag, runs_nothing);
  if (args.suite.empty()) {
    const std::string needs_suite =
        "with --merge, the suite's flags are only checked against the shards when SUITE is given too";
    RefuseIfGiven(*args.bench.cmd, "--split", needs_suite);
    RefuseBenchFlags(args.bench, needs_suite);
  }
  std::optional<nlohmann::json> expected;
  if (!args.suite.empty()) {
    expected =
        SuiteIdentity(ReadSuite(args.suite), args.split, BenchSettingsJson(ResolveBench(args.bench, args.run.threads)));
  }
  CheckSuiteReportFolder(args.output);
  const FolderLock lock(args.output, FolderLock::IfBusy::kRefuse);
  return WriteAndPrintReport(MergeSuite(args.merge, expected ? &*expected : nullptr), args.output);
}

int SuiteCommand(const SuiteArgs& args) {
  if (!args.merge.empty()) return MergeCommand(args);
  if (args.suite.empty())
    throw InputError("suite", "a SUITE file is needed (or --merge DIR... to combine shard outputs)");
  const Suite suite = ReadSuite(args.suite);
  SuiteOptions options;
  options.output_dir = args.output;
  options.split = args.split;
  options.run = args.run;
  if (args.shard) options.shard = ParseShard(*args.shard);
  const BenchOptions bench = ResolveBench(args.bench, args.run.threads);
  options.run.cancel = CancelOnInterrupt();
  const std::vector<SuiteRunSpec> runs = SuiteRuns(suite, options.split);
  if (runs.empty()) throw InputError("--split", "suite " + suite.name + " has no sequence in split " + options.split);
  std::printf("suite %s: %zu runs (split %s)", suite.name.c_str(), runs.size(), options.split.c_str());
  if (options.shard.count > 1) {
    std::printf(", shard %s does %zu", options.shard.Name().c_str(), ShardOf(runs, options.shard).size());
  }
  std::printf("\n");
  // Held from the first run to the report (RunSuite and WriteSuiteReport take it again): a second
  // suite into this folder is refused by name.
  const FolderLock lock(args.output, FolderLock::IfBusy::kRefuse);
  const std::vector<SuiteRunResult> results =
      RunSuite(suite, bench, options, [](int position, int total, const SuiteRunSpec& run, bool kept) {
        std::printf("run %d/%d: %s%s\n", position, total, run.name.c_str(), kept ? " (kept from an earlier run)" : "");
        std::fflush(stdout);
      });
  if (options.shard.count == 1) return WriteAndPrintReport(MergeSuite({args.output}), args.output);
  // A shard succeeds once each of its runs finished or failed: the merge reports the failed ones
  // (and exits 1), as the unsharded suite does; a shard that stopped early exits non-zero.
  size_t failed = 0;
  for (const SuiteRunResult& r : results) {
    if (r.ok()) continue;
    ++failed;
    std::fprintf(stderr, "failed: %s: %s\n", r.name.c_str(), r.error.c_str());
  }
  std::printf(
      "shard %s done in %s (runs: %zu, failed: %zu, listed by the merged report); when every shard is done: "
      "hoilcd suite --merge DIR... -o OUT\n",
      options.shard.Name().c_str(), args.output.c_str(), results.size(), failed);
  return 0;
}

}  // namespace

Command AddSuiteCommand(CLI::App* app) {
  auto args = std::make_shared<SuiteArgs>();
  CLI::App* cmd = app->add_subcommand(
      "suite", "run every sequence x seed of a suite file; mean MRR over sequences with 95 % intervals, ranks, wins");
  cmd->footer(
      "Each run's report goes to OUT/runs/<sequence>-seed<S>/ and is kept on a rerun when its scene\n"
      "and bench settings are unchanged. A run that fails is listed in the report with its error;\n"
      "the others go on, and the command exits 1 at the end.\n"
      "--shard I/N runs only every N-th run starting at I (0 <= I < N) of the split's runs sorted by\n"
      "name, for job arrays, and writes no report; OUT/suite.json marks the shard and the suite's\n"
      "identity. A shard exits 0 when its failed runs are recorded: the merge lists them.\n"
      "--merge DIR... -o OUT writes the report of the shards' runs (nothing is rendered), the same\n"
      "bytes as an unsharded suite's, and refuses shards of different suites, a missing or repeated\n"
      "shard and a run neither finished nor failed. With SUITE and the shards' --split and bench\n"
      "flags it also checks the shards ran exactly that suite. See docs/guide/suites.md.");
  cmd->add_option("suite", args->suite, "suite file (JSON); optional with --merge");
  cmd->add_option("-o,--output", args->output,
                  "suite folder: runs/, scenes/, suite_report.json, suite_report.md (the merge's: the report)")
      ->required();
  cmd->add_option("--split", args->split, "which sequences to run")
      ->check(CLI::IsMember({"dev", "test", "all"}))
      ->capture_default_str();
  AddManyRunsCacheFlags(cmd, &args->run);
  AddShardFlag(cmd, &args->shard, "run only part I of N (0-based, e.g. $SLURM_ARRAY_TASK_ID/4)");
  cmd->add_option("--merge", args->merge, "write the report of these suite or shard folders into OUT")
      ->type_name("DIR...");
  AddThreadsFlag(cmd, &args->run.threads);
  AddBenchFlags(cmd, &args->bench);
  return {cmd, [args] { return SuiteCommand(*args); }};
}

}  // namespace hoilcd
