// hoilcd export-mcap DATASET -o FILE.mcap: the dataset as a ROS 2 bag (MCAP) for ros2 bag play and
// Foxglove (docs/guide/ros2.md).
#include "export_mcap.h"

#include <cstdio>
#include <memory>

#include "command.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/safe_text.h"
#include "shared.h"

namespace hoilcd {

void PrintMcapExport(const McapExportResult& r) {
  std::printf("wrote %s: %d frames, %llu messages, %.1f MB in %.1f s (%.0f frames/s)\n", r.path.c_str(), r.frames,
              static_cast<unsigned long long>(r.messages), r.bytes / 1e6, r.seconds,
              r.seconds > 0 ? r.frames / r.seconds : 0.0);
  for (const auto& [topic, count] : r.topics) {
    std::printf("  %-28s %llu\n", topic.c_str(), static_cast<unsigned long long>(count));
  }
}

Command AddExportMcapCommand(CLI::App* app) {
  struct Args {
    std::string dataset, output, compression = "zstd";
    int threads = 0;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app->add_subcommand("export-mcap", "the dataset as a ROS 2 bag in MCAP (ros2 bag play, Foxglove)");
  cmd->add_option("dataset", args->dataset, "dataset folder written by hoilcd render")->required();
  cmd->add_option("-o,--output", args->output, "the .mcap file to write (replaced atomically)")->required();
  cmd->add_option("--compression", args->compression, "chunk compression: zstd or none")->capture_default_str();
  AddThreadsFlag(cmd, &args->threads);
  return {cmd, [args] {
            McapExportOptions options;
            if (!ParseMcapCompression(args->compression, &options.compression)) {
              throw InputError("--compression", "expected zstd or none, got '" + SafeText(args->compression) + "'");
            }
            options.threads = args->threads;
            PrintMcapExport(ExportMcap(args->dataset, args->output, options));
            return 0;
          }};
}

}  // namespace hoilcd
