// hoilcd bench DATASET: run loop-closure methods on a dataset folder and write the report.
#include <cstdio>
#include <memory>

#include "command.h"
#include "hoilcd/bench/evaluation/evaluate.h"
#include "hoilcd/bench/evaluation/scores_file.h"
#include "hoilcd/bench/report/gate.h"
#include "hoilcd/bench/report/online_report.h"
#include "hoilcd/bench/report/report.h"
#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/util/file_io.h"
#include "shared.h"

namespace hoilcd {
namespace {

struct BenchCommandArgs {
  std::string dataset;
  std::string report_dir;
  std::string dump_scores;
  int threads = 0;
  BenchArgs bench;
  GateArgs gate;
  bool online = false;
  ShortlistOptions shortlist;
};

// --online: frames in order, each query against a shortlist of the past (online.h). The gate and
// --junit read its report.json as they read the offline one's; the flags of what it does not
// compute (SLAM, strata, every pair's scores) are refused by name.
int OnlineBenchCommand(const BenchCommandArgs& args, const Dataset& dataset, const std::string& out) {
  const CLI::App& cmd = *args.bench.cmd;
  RefuseIfGiven(cmd, "--dump-scores",
                "not with --online: an online query is scored against its shortlist only, so there is no score of "
                "every pair for hoilcd evaluate; drop --online to dump them");
  const std::string no_slam = "not with --online: the online bench runs no SLAM back end";
  for (const char* flag : {"--slam", "--slam-backend", "--loop-threshold"}) RefuseIfGiven(cmd, flag, no_slam);
  RefuseIfGiven(cmd, "--strata",
                "not with --online: the online report has no strata (its figures are per method and per recording "
                "run); drop --online to split by conditions");
  if (args.shortlist.index == "flat") {
    RefuseIfGiven(cmd, "--shortlist-search-depth",
                  "applies to --shortlist-index hnsw only (the flat index searches every frame)");
  }
  const BenchOptions options = ResolveBench(args.bench, args.threads);
  const nlohmann::json baseline = ReadBaseline(args.gate, "online");
  CheckReportFolder(out);
  const OnlineResult result = RunOnlineBench(dataset, options, args.shortlist);
  WriteOnlineReport(result, dataset, out);
  PrintWarnings(result.skipped);
  std::printf("%s", OnlineResultToMarkdown(result).c_str());
  std::printf("report: %s/report.md\n", out.c_str());
  return ApplyGate(args.gate, baseline, ReadReportJson(out + "/report.json"));
}

int BenchCommand(const BenchCommandArgs& args) {
  const Dataset dataset = Dataset::Open(args.dataset, Verify::kOnRead, args.threads);
  PrintWarnings(dataset.warnings());
  const std::string out = args.report_dir.empty() ? args.dataset + "/report" : args.report_dir;
  if (args.online) return OnlineBenchCommand(args, dataset, out);
  const BenchOptions options = ResolveBench(args.bench, args.threads);
  const nlohmann::json baseline = ReadBaseline(args.gate);
  ReportTiming timing;
  const BenchResult result = BenchAndWriteReport(dataset, options, &timing, out);
  if (!args.dump_scores.empty()) {
    for (const MethodRun& run : result.runs) {
      WriteFileAtomic(args.dump_scores + "/" + run.name + ".csv", ScoresToCsv(result.queries, run.scores));
    }
  }
  PrintOutcome(result, out);
  return ApplyGate(args.gate, baseline, ReadReportJson(out + "/report.json"));
}

}  // namespace

Command AddBenchCommand(CLI::App* app) {
  auto args = std::make_shared<BenchCommandArgs>();
  CLI::App* cmd = app->add_subcommand("bench", "evaluate loop-closure methods on a dataset folder");
  cmd->add_option("dataset", args->dataset, "dataset folder written by hoilcd render")->required();
  cmd->add_option("-o,--output", args->report_dir, "report folder (default DATASET/report)");
  AddThreadsFlag(cmd, &args->threads);
  cmd->add_option("--dump-scores", args->dump_scores,
                  "write each method's scores as DIR/<method>.csv (query,reference,score), for hoilcd evaluate")
      ->type_name("DIR");
  AddBenchFlags(cmd, &args->bench);
  AddGateFlags(cmd, &args->gate);
  CLI::Option* online = cmd->add_flag(
      "--online", args->online,
      "online loop closure: frames in order, the database only frames older than the exclusion window, each "
      "query scored on a FAISS shortlist of its past (docs/guide/protocol.md)");
  const std::vector<OptionInfo> shortlist = ShortlistOptions::Table().List();
  AddTableFlag(cmd, "--shortlist-k", shortlist, "k", &args->shortlist.k)->needs(online);
  AddTableFlag(cmd, "--shortlist-index", shortlist, "index", &args->shortlist.index)->needs(online);
  AddTableFlag(cmd, "--shortlist-search-depth", shortlist, "hnsw_search_depth", &args->shortlist.hnsw_search_depth)
      ->needs(online);
  return {cmd, [args] { return BenchCommand(*args); }};
}

}  // namespace hoilcd
