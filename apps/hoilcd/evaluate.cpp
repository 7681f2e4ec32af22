// hoilcd evaluate DATASET --scores FILE: the benchmark's protocol, labels and metrics applied to
// the scores of a method hoilcd did not run.
#include <cstdio>
#include <filesystem>
#include <memory>

#include "command.h"
#include "hoilcd/bench/evaluation/evaluate.h"
#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/file_io.h"
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
};

int EvaluateCommand(const EvaluateArgs& args) {
  const Dataset dataset = Dataset::Open(args.dataset, Verify::kOnRead);
  PrintWarnings(dataset.warnings());
  const nlohmann::json baseline = ReadBaseline(args.gate);
  std::string name = args.name;
  if (name.empty()) name = std::filesystem::path(args.scores).stem().string();
  if (name.empty()) throw InputError("--name", "a method name (the scores file name has none)");
  const MethodReport report = Evaluate(dataset, ReadScoresFile(args.scores, dataset.num_frames()), name, args.protocol);
  const nlohmann::json json = EvaluateReportJson(dataset, args.protocol, report, "scores from " + args.scores);
  const MethodMetrics& m = report.metrics;
  std::printf("%s (%s ground truth): MRR %.4f, R@1 %.4f, R@5 %.4f, PR-AUC %.4f; %d queries scored, %d skipped\n",
              name.c_str(), args.protocol.ground_truth.c_str(), m.mrr, m.recall_at_1, m.recall_at_5, m.pr_auc,
              m.queries_scored, m.queries_skipped);
  if (!args.output.empty()) {
    WriteFileAtomic(args.output, json.dump(2) + "\n");
    std::printf("report: %s\n", args.output.c_str());
  }
  return ApplyGate(args.gate, baseline, json);
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
  cmd->add_option("-o,--output", args->output, "write a report.json of this method here");
  AddProtocolFlags(cmd, &args->protocol);
  AddGateFlags(cmd, &args->gate);
  return {cmd, [args] { return EvaluateCommand(*args); }};
}

}  // namespace hoilcd
