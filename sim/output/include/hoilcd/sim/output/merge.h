// hoilcd merge: joins the shard folders of one sequence (`hoilcd render --shard I/N`) into the
// dataset the unsharded render writes, byte for byte, manifest included: frame files hard-linked
// (copied across file systems) and side files copied, each checked against its shard's checksum,
// persons.json joined, thermal.mp4 encoded
// from every frame (in video mode the thermal PNGs then replaced by its decoded frames) and the
// manifest. Every shard and the output folder are checked before anything is written.
#pragma once

#include <string>
#include <vector>

namespace hoilcd {

struct MergeResult {
  int frames = 0;            // frames in the merged dataset
  int shards = 0;            // shard folders joined
  double seconds = 0;        // wall time, s
  double video_seconds = 0;  // encoding (and in video mode decoding) thermal.mp4, s
};

// Throws InputError, before writing to output_dir, naming the folder and what was expected when
// the shards are of different scenes, seeds, simulator versions, --outputs, --frames or shard
// counts, when a shard is repeated, missing or incomplete, or when output_dir holds anything but
// an earlier dataset of the same render, frame count included, or another process writes into
// it (the rules of a render's folder, its lock included). A re-run over its own output, whole or
// killed half way, gives the same bytes and leaves no temp file. A file that does not
// match its shard's checksum is an InputError naming it, found while copying: the output is then
// left partial (its manifest says so) and a re-run after re-rendering that shard finishes it.
MergeResult MergeShards(const std::vector<std::string>& shard_dirs, const std::string& output_dir, int threads);

}  // namespace hoilcd
