// hoilcd merge DIR... -o DIR: join the shard folders of one sequence (hoilcd render --shard I/N)
// into the dataset the unsharded render writes, byte for byte.
#include "hoilcd/sim/output/merge.h"

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "command.h"
#include "shared.h"

namespace hoilcd {
namespace {

struct MergeArgs {
  std::vector<std::string> shards;
  std::string output;
  int threads = 0;
};

int MergeCommand(const MergeArgs& args) {
  const MergeResult r = MergeShards(args.shards, args.output, args.threads);
  std::printf("merged %d shards (%d frames) into %s in %.1f s (thermal.mp4: %.1f s)\n", r.shards, r.frames,
              args.output.c_str(), r.seconds, r.video_seconds);
  return 0;
}

}  // namespace

Command AddMergeCommand(CLI::App* app) {
  auto args = std::make_shared<MergeArgs>();
  CLI::App* cmd = app->add_subcommand(
      "merge", "join the shard folders of hoilcd render --shard I/N into the dataset the unsharded render writes");
  cmd->add_option("shards", args->shards, "the N shard folders, in any order")->required();
  cmd->add_option("-o,--output", args->output,
                  "dataset folder: new, empty, or holding an earlier dataset of the same render")
      ->required();
  AddThreadsFlag(cmd, &args->threads);
  return {cmd, [args] { return MergeCommand(*args); }};
}

}  // namespace hoilcd
