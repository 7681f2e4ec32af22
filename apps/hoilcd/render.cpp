// hoilcd render SCENE -o DIR: render a scene's sequence (or its first N frames) into a dataset folder;
// with --shard I/N only the I-th contiguous part of its frames, into a shard folder for hoilcd merge.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "command.h"
#include "export_mcap.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/core/util/shard.h"
#include "hoilcd/sim/output/sequence.h"
#include "shared.h"

namespace hoilcd {
namespace {

// The bag `--outputs ...,mcap` writes into the dataset folder (a name dataset_folder.h counts as hoilcd's).
constexpr char kRenderBagName[] = "ros2.mcap";

// Takes "mcap" out of a comma-separated --outputs list: the rest chooses the dataset's outputs as
// before ("" for mcap alone: all of them); true when it was there.
bool TakeMcapOutput(std::string* outputs) {
  std::string rest;
  bool mcap = false;
  size_t start = 0;
  while (start <= outputs->size()) {
    const size_t comma = std::min(outputs->find(',', start), outputs->size());
    const std::string name = outputs->substr(start, comma - start);
    if (name == "mcap") {
      mcap = true;
    } else {
      rest += (rest.empty() ? "" : ",") + name;
    }
    start = comma + 1;
  }
  if (mcap) *outputs = rest;
  return mcap;
}

struct RenderArgs {
  SceneArgs scene;
  SequenceOptions options;
  std::optional<std::string> shard;  // --shard I/N (unset: the whole sequence)
};

int RenderCommand(const RenderArgs& args) {
  SequenceOptions o = args.options;
  if (args.shard) o.shard = ParseShard(*args.shard);  // before the scene: a bad flag fails first
  const bool mcap = TakeMcapOutput(&o.outputs);
  if (mcap && args.shard) {
    throw InputError("--outputs",
                     "mcap needs the whole sequence, not a shard: run hoilcd export-mcap on the "
                     "dataset hoilcd merge writes");
  }
  const Scene scene = LoadSceneArgs(args.scene);
  o.cancel = CancelOnInterrupt();
  const SequenceResult r = RenderSequence(scene, o);
  PrintWarnings(r.warnings);
  const int threads = ResolveThreadCount(o.threads);
  std::printf("rendered %d frames (%d kept from an earlier run) into %s in %.1f s (%.1f frames/s, %d thread%s)\n",
              r.frames_rendered, r.frames_reused, o.output_dir.c_str(), r.seconds,
              r.seconds > 0 ? r.frames_rendered / r.seconds : 0.0, threads, threads == 1 ? "" : "s");
  // The encoder runs on a writer thread while later frames render: its time is not all added.
  std::printf(
      "thermal.mp4: %.2f s of work, %.1f %% of the render's wall time (its encoding runs beside the rendering)\n",
      r.video_seconds, r.seconds > 0 ? 100.0 * r.video_seconds / r.seconds : 0.0);
  if (mcap) {
    McapExportOptions mcap_options;
    mcap_options.threads = o.threads;
    PrintMcapExport(ExportMcap(o.output_dir, o.output_dir + "/" + kRenderBagName, mcap_options));
  }
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
                  "the manifest lists them, and hoilcd bench needs thermal), and mcap: also DIR/ros2.mcap, the "
                  "dataset as a ROS 2 bag (hoilcd export-mcap; with mcap alone, every other output too)");
  return {cmd, [args] { return RenderCommand(*args); }};
}

}  // namespace hoilcd
