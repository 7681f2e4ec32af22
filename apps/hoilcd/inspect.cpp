// hoilcd inspect DATASET: what a user checks before trusting a sequence.
#include "hoilcd/bench/report/inspect.h"

#include <cstdio>
#include <memory>

#include "command.h"
#include "hoilcd/core/dataset/dataset.h"
#include "shared.h"

namespace hoilcd {
namespace {

struct InspectArgs {
  std::string dataset;
  std::string output;
  bool json = false;
  ProtocolOptions protocol;
};

int InspectCommand(const InspectArgs& args) {
  if (!args.output.empty()) CheckInspectFolder(args.output);  // a folder it may not use fails before the work
  // Every file inspect reads is checked against manifest.json as the bench checks it: figures of a
  // changed poses.csv would describe a dataset nobody rendered.
  const Dataset dataset = Dataset::Open(args.dataset, Verify::kOnRead);
  PrintWarnings(dataset.warnings());
  const InspectReport report = InspectDataset(dataset, args.protocol);
  if (!args.output.empty()) WriteInspectFolder(report, args.output);
  const std::string text =
      args.json ? report.ToJson().dump(2) + "\n" : "dataset " + args.dataset + "\n" + report.ToText();
  std::printf("%s", text.c_str());
  return 0;
}

}  // namespace

Command AddInspectCommand(CLI::App* app) {
  auto args = std::make_shared<InspectArgs>();
  CLI::App* cmd =
      app->add_subcommand("inspect",
                          "what to check before trusting a dataset: laps, lap-to-lap path difference, odometry drift, "
                          "camera jitter, people in view, occlusion, odometric vs true ground truth");
  cmd->add_option("dataset", args->dataset, "dataset folder written by hoilcd render")->required();
  cmd->add_flag("--json", args->json, "print the figures as JSON instead of text");
  cmd->add_option("-o,--output", args->output,
                  "also write the figures as DIR/inspect.json (a new or empty folder, or an earlier inspect's)")
      ->type_name("DIR");
  AddProtocolAndRadiusFlags(cmd, &args->protocol);
  return {cmd, [args] { return InspectCommand(*args); }};
}

}  // namespace hoilcd
