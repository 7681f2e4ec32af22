// hoilcd evaluate DATASET --scores FILE: the benchmark's protocol, labels and metrics applied to
// the scores of a method hoilcd did not run.
#include "hoilcd/bench/evaluation/evaluate.h"

#include <cstdio>
#include <filesystem>
#include <memory>

#include "command.h"
#include "hoilcd/bench/report/report.h"
#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/util/error.h"
#include "shared.h"

namespace hoilcd {
namespace {

struct EvaluateArgs {
  std::string dataset;
  std::string scores;
  std::string name;
  std::string output;
  ProtocolOptions protocol;
  GateArgs gate;
  const CLI::App* cmd = nullptr;
};

int EvaluateCommand(const EvaluateArgs& args) {
  CheckProtocolFlagsApply(*args.cmd, args.protocol);
  const Dataset dataset = Dataset::Open(args.dataset, Verify::kOnRead);
  PrintWarnings(dataset.warnings());
  const nlohmann::json baseline = ReadBaseline(args.gate);
  std::string name = args.name;
  if (name.empty()) name = std::filesystem::path(args.scores).stem().string();
  if (name.empty()) throw InputError("--name", "a method name (the scores file name has none)");
  if (!args.output.empty()) CheckReportFolder(args.output);  // a folder it may not use fails before the work
  // A dataset without a true match fails before the scores are read: their metrics are undefined.
  const Labelling labelling = LabelQueries(dataset, args.protocol);
  if (const std::string why = NoTrueMatchReason(labelling); !why.empty()) throw InputError(args.dataset, why);
  const ScoreMatrix scores = ReadScoresFile(args.scores, dataset.num_frames());
  const std::string description = "scores from " + args.scores;
  const MethodReport report = args.output.empty()
                                  ? EvaluateLabelled(dataset, labelling, scores, name)
                                  : EvaluateAndWriteReport(dataset, labelling, scores, name, description, args.output);
  PrintWarnings(report.warnings);
  const MethodMetrics& m = report.metrics;
  std::printf("%s (%s ground truth): MRR %.4f, R@1 %.4f, R@5 %.4f, PR-AUC %.4f; %d queries scored, %d skipped\n",
              report.name.c_str(), args.protocol.ground_truth.c_str(), m.mrr, m.recall_at_1, m.recall_at_5, m.pr_auc,
              m.queries_scored, m.queries_skipped);
  if (!args.output.empty()) std::printf("report: %s/report.md\n", args.output.c_str());
  return ApplyGate(args.gate, baseline, EvaluateReportJson(dataset, args.protocol, report, description));
}

}  // namespace

Command AddEvaluateCommand(CLI::App* app) {
  auto args = std::make_shared<EvaluateArgs>();
  CLI::App* cmd = app->add_subcommand(
      "evaluate", "apply the benchmark's protocol, labels and metrics to scores of a method hoilcd did not run");
  cmd->add_option("dataset", args->dataset, "dataset folder written by hoilcd render")->required();
  cmd->add_option("--scores", args->scores,
                  "CSV with header query,reference,score (frame indices; pairs left out are unscored) or "
                  ".npy dense frames x frames float32/float64 matrix (NaN = unscored)")
      ->required();
  cmd->add_option("--name", args->name, "method name in the report (default: the scores file's name)");
  cmd->add_option("-o,--output", args->output,
                  "report folder of this method: report.json, queries.csv, report.md, figures (a new or empty "
                  "folder, or an earlier report's)")
      ->type_name("DIR");
  AddProtocolFlags(cmd, &args->protocol);
  AddGateFlags(cmd, &args->gate);
  args->cmd = cmd;
  return {cmd, [args] { return EvaluateCommand(*args); }};
}

}  // namespace hoilcd
