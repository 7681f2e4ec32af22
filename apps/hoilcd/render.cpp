// hoilcd render SCENE -o DIR: render a scene's sequence (or its first N frames) into a dataset folder;
// with --shard I/N only the I-th contiguous part of its frames, into a shard folder for hoilcd merge.
#include <cstdio>
#include <memory>
#include <optional>

#include "command.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/core/util/shard.h"
#include "hoilcd/sim/output/sequence.h"
#include "shared.h"

namespace hoilcd {
namespace {

struct RenderArgs {
  SceneArgs scene;
  SequenceOptions options;
  std::optional<std::string> shard;  // --shard I/N (unset: the whole sequence)
};

int RenderCommand(const RenderArgs& args) {
  SequenceOptions o = args.options;
  if (args.shard) o.shard = ParseShard(*args.shard);  // before the scene: a bad flag fails first
  const Scene scene = LoadSceneArgs(args.scene);
  o.cancel = CancelOnInterrupt();
  const SequenceResult r = RenderSequence(scene, o);
  PrintWarnings(r.warnings);
  const int threads = ResolveThreadCount(o.threads);
  std::printf("rendered %d frames (%d kept from an earlier run) into %s in %.1f s (%.1f frames/s, %d thread%s)\n",
              r.frames_rendered, r.frames_reused, o.output_dir.c_str(), r.seconds,
              r.seconds > 0 ? r.frames_rendered / r.seconds : 0.0, threads, threads == 1 ? "" : "s");
  // The encoder runs on a writer thread while later frames render: its time is not all added.
  std::printf("thermal.mp4: %.2f s of work, %.1f %% of the render's wall time (its encoding runs beside the rendering)\n",
              r.video_seconds, r.seconds > 0 ? 100.0 * r.video_seconds / r.seconds : 0.0);
  return 0;
}

}  // namespace

Command AddRenderCommand(CLI::App* app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app->add_subcommand("render", "render a scene's sequence into a dataset folder");
  AddSceneFlags(cmd, &args->scene, true);
  cmd->add_option("-o,--output", args->options.output_dir,
                  "dataset folder (resumed if it holds an interrupted render of the same scene)")
      ->required();
  cmd->add_option("--frames", args->options.frames, "render only the first N frames (0: all)")
      ->check(NumberIn(OptionRange().AtLeast(0)));
  AddThreadsFlag(cmd, &args->options.threads);
  AddShardFlag(cmd, &args->shard,
               "I/N: render only the I-th of N contiguous parts of the frames (0 <= I < N) into a shard folder; "
               "hoilcd merge joins the N folders into the dataset the whole render writes");
  cmd->add_option("--outputs", args->options.outputs,
                  "comma-separated outputs to write: thermal, radiometric, exr, video, persons (default: all; "
                  "the manifest lists them, and hoilcd bench needs thermal)");
  return {cmd, [args] { return RenderCommand(*args); }};
}

}  // namespace hoilcd
