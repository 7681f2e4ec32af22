// hoilcd export-coco DATASET -o DIR: the dataset's person keypoints as COCO keypoints JSON.
#include <cstdio>
#include <memory>

#include "command.h"
#include "hoilcd/bench/export/coco_export.h"
#include "shared.h"

namespace hoilcd {

Command AddExportCocoCommand(CLI::App* app) {
  struct Args {
    std::string dataset, output;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app->add_subcommand("export-coco", "the dataset's person keypoints as COCO keypoints JSON");
  cmd->add_option("dataset", args->dataset, "dataset folder written by hoilcd render")->required();
  cmd->add_option("-o,--output", args->output, "folder for person_keypoints.json")->required();
  return {cmd, [args] {
            std::printf("wrote %s\n", ExportCoco(args->dataset, args->output).c_str());
            return 0;
          }};
}

}  // namespace hoilcd
