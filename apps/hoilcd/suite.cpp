// hoilcd suite SUITE -o OUT: every (sequence, seed) of a suite file rendered and benched, and a
// report of each method's mean over runs with its interval, ranks and paired wins.
#include <cstdio>
#include <memory>

#include "command.h"
#include "hoilcd/bench/pipeline/suite.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/text.h"
#include "shared.h"

namespace hoilcd {
namespace {

struct SuiteArgs {
  std::string suite;
  std::string output;
  std::string split = "all";
  RunOptions run;
  BenchArgs bench;
};

int SuiteCommand(const SuiteArgs& args) {
  const Suite suite = ReadSuite(args.suite);
  SuiteOptions options;
  options.output_dir = args.output;
  options.split = args.split;
  options.run = args.run;
  const BenchOptions bench = ResolveBench(args.bench, args.run.threads);
  options.run.cancel = CancelOnInterrupt();
  const std::vector<SuiteRunSpec> runs = SuiteRuns(suite, options.split);
  if (runs.empty()) throw InputError("--split", "suite " + suite.name + " has no sequence in split " + options.split);
  std::printf("suite %s: %zu runs (split %s)\n", suite.name.c_str(), runs.size(), options.split.c_str());
  const SuiteSummary summary = RunSuite(suite, bench, options, [](int position, int total, const SuiteRunSpec& run, bool kept) {
    std::printf("run %d/%d: %s%s\n", position, total, run.name.c_str(), kept ? " (kept from an earlier run)" : "");
    std::fflush(stdout);
  });
  for (const SuiteMethodSummary& m : summary.methods) {
    std::printf("%-16s MRR %s [%s, %s]  mean rank %s\n", m.method.c_str(), Fixed(m.mean_mrr, 3).c_str(),
                Fixed(m.mrr_interval.low, 3).c_str(), Fixed(m.mrr_interval.high, 3).c_str(), Fixed(m.mean_rank, 2).c_str());
  }
  for (const auto& [run, error] : summary.failed) std::fprintf(stderr, "failed: %s: %s\n", run.c_str(), error.c_str());
  std::printf("report: %s/suite_report.md (and suite_report.json)\n", args.output.c_str());
  if (!summary.failed.empty()) {
    std::fprintf(stderr, "error: %zu of %zu runs failed\n", summary.failed.size(), runs.size());
    return 1;
  }
  return 0;
}

}  // namespace

Command AddSuiteCommand(CLI::App* app) {
  auto args = std::make_shared<SuiteArgs>();
  CLI::App* cmd = app->add_subcommand(
      "suite", "run every sequence x seed of a suite file; mean MRR over runs with 95 % intervals, ranks, wins");
  cmd->footer(
      "Each run's report goes to OUT/runs/<sequence>-seed<S>/ and is kept on a rerun when its scene\n"
      "and bench settings are unchanged. A run that fails is listed in the report with its error;\n"
      "the others go on, and the command exits 1 at the end. See docs/guide/suites.md.");
  cmd->add_option("suite", args->suite, "suite file (JSON)")->required();
  cmd->add_option("-o,--output", args->output, "suite folder: runs/, scenes/, suite_report.json, suite_report.md")
      ->required();
  cmd->add_option("--split", args->split, "which sequences to run")
      ->check(CLI::IsMember({"dev", "test", "all"}))
      ->capture_default_str();
  cmd->add_option("--cache", args->run.cache_dir, "folder of cached datasets (shared by every run)");
  AddThreadsFlag(cmd, &args->run.threads);
  AddBenchFlags(cmd, &args->bench);
  return {cmd, [args] { return SuiteCommand(*args); }};
}

}  // namespace hoilcd
