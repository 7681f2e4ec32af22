// Renders a whole recording session into a dataset folder (SPEC.md "Dataset folder"): the robot
// drives its route, people move, each frame is ray cast, passed through the sensor model and
// written atomically; a scene with runs (SceneOfRun) renders each run after the other, each with
// its own world, robot run and camera, and writes runs.json. Re-running the same command resumes: frames already
// written and listed in the manifest with matching checksums are kept, the rest are rendered. thermal.mp4 is written
// last, from the uncompressed 8-bit frames; in video mode (camera.video.enabled) the thermal PNGs are then replaced by
// its decoded frames. A shard renders a part of the frames (options.shard); hoilcd merge (merge.h) joins the shards.
#pragma once

#include <atomic>
#include <optional>
#include <string>
#include <vector>

#include "hoilcd/core/util/option_table.h"
#include "hoilcd/core/util/shard.h"
#include "hoilcd/sim/scene/scene.h"

namespace hoilcd {

// How one `hoilcd render` runs (command-line flags, not scene values).
struct SequenceOptions {
  std::string output_dir;       // dataset folder (created if missing)
  int frames;                   // frames: render only the first N (0 = the scene's count)
  int threads;                  // worker threads (0 = the CPUs this process may use)
  int checkpoint_every_frames;  // frames: the manifest is rewritten this often (resume granularity)
  std::string outputs;          // comma-separated: thermal, radiometric, exr, video, persons (default all)
  const std::atomic<bool>* cancel = nullptr;  // set (e.g. by SIGINT) to stop after the current frame; not in the table
  int cancel_after_frames =
      -1;  // test hook: frames: stop as `cancel` does once this call has done this many (-1 = never); not in the table
  // --shard I/N: render only the I-th contiguous part of the frames into a shard folder, which
  // hoilcd merge joins with the others (none: the whole sequence); not in the table.
  std::optional<Shard> shard;

  SequenceOptions();  // the registered defaults
  // Every field once: name, unit, default, range, description.
  static const OptionTable<SequenceOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

struct SequenceResult {
  int frames_total = 0;      // frames in the dataset when done
  int frames_rendered = 0;   // rendered by this call
  int frames_reused = 0;     // kept from an earlier, interrupted run
  double seconds = 0;        // wall time of this call
  double video_seconds = 0;  // encoding (and in video mode decoding) thermal.mp4, s; encoding overlaps rendering
  bool complete = false;
  std::vector<std::string> warnings;  // what the scene asked for and did not get (World::warnings)
};

// Thrown when SequenceOptions::cancel was set; the dataset is consistent and resumable.
class RenderInterrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// What renders this build's datasets (the manifest's hoilcd_version): the hoilcd version plus a
// simulator revision that is bumped whenever a change alters rendered bytes, so a resume or a
// dataset cache never mixes or reuses frames of another simulator.
std::string SimulatorVersion();

// Everything a render checks before its first frame (the world and its furniture and people, the
// robot's run among them, the crowd's plan, the camera's, video's and renderer's options), without
// rendering: throws the InputError a render would. Returns the warnings a render would print.
// `hoilcd validate` runs it, so a scene it passes renders.
std::vector<std::string> CheckSceneRenders(const Scene& scene);

// Throws InputError when the folder holds a dataset of another scene, seed, simulator version,
// frame count, --outputs or --shard, or when another process renders into it (the folder's lock,
// core/util/folder_lock.h, is held from the first check to the last write). With options.shard, the folder is a shard:
// frames ContiguousPart(shard, frames), the whole sequence's poses, events and footprints, persons.json of its frames
// and no thermal.mp4 (in video mode its thermal PNGs stay uncompressed); the state a frame carries over from earlier
// ones (the sensor model's) is replayed as a resume does, so its frames are those of the unsharded render, byte for
// byte.
SequenceResult RenderSequence(const Scene& scene, const SequenceOptions& options);

}  // namespace hoilcd
