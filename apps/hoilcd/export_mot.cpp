// hoilcd export-mot DATASET -o DIR: ground-truth person boxes and the DLCD front end's tracks in
// MOTChallenge format, for TrackEval.
#include <cstdio>
#include <memory>

#include "command.h"
#include "hoilcd/bench/export/mot_export.h"
#include "hoilcd/core/dataset/dataset.h"
#include "shared.h"

namespace hoilcd {

Command AddExportMotCommand(CLI::App* app) {
  struct Args {
    std::string dataset, output;
    int threads = 0;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app->add_subcommand(
      "export-mot", "ground-truth person boxes and the DLCD front end's tracks in MOTChallenge format (TrackEval)");
  cmd->add_option("dataset", args->dataset, "dataset folder written by hoilcd render")->required();
  cmd->add_option("-o,--output", args->output, "folder for gt/ and trackers/ (TrackEval's GT_FOLDER/TRACKERS_FOLDER)")
      ->required();
  AddThreadsFlag(cmd, &args->threads);
  return {cmd, [args] {
            const Dataset dataset = Dataset::Open(args->dataset, Verify::kOnRead);
            BenchOptions options;
            options.threads = args->threads;
            const MotExport e = ExportMot(dataset, options, args->output);
            std::printf("wrote %s and %s (sequence %s; TrackEval: --BENCHMARK HOILCD --SPLIT_TO_EVAL train)\n",
                        e.ground_truth.c_str(), e.tracks.c_str(), e.sequence.c_str());
            return 0;
          }};
}

}  // namespace hoilcd
