#include "hoilcd/sim/output/merge.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>
#include <optional>

#include <unistd.h>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/dataset/dataset_folder.h"
#include "hoilcd/core/util/folder_lock.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/core/util/progress.h"
#include "hoilcd/sim/output/sequence.h"
#include "hoilcd/sim/output/video_files.h"
#include "hoilcd/sim/scene/scene.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

// The whole sequence's side files: the same in every shard, copied from the first; runs.json only
// in a sequence of several recording runs.
const char* const kSideFiles[] = {"poses.csv",       "poses_tum.txt", "events.json",
                                  "footprints.json", "scene.json",    "runs.json"};
bool Optional(const std::string& side_file) { return side_file == "runs.json"; }

struct ShardFolder {
  std::string dir;
  DatasetManifest manifest;
  const DatasetShard& part() const { return *manifest.shard; }
};

std::string FramesText(int begin, int end) {
  return "frames " + std::to_string(begin) + " to " + std::to_string(end - 1);
}

// The shard's manifest, with what makes it one: a shard's folder, this simulator's, finished.
ShardFolder ReadShard(const std::string& dir) {
  const std::string path = dir + "/manifest.json";
  if (!fs::is_regular_file(path)) {
    throw InputError(dir,
                     "no manifest.json: not a shard folder (write one with hoilcd render SCENE -o DIR --shard I/N)");
  }
  ShardFolder shard{dir, DatasetManifest::FromJson(ReadFileBytes(path), path)};
  const DatasetManifest& m = shard.manifest;
  if (!m.shard) {
    throw InputError(dir,
                     "is a whole dataset (rendered without --shard), not a shard; hoilcd merge joins the "
                     "folders of hoilcd render --shard I/N");
  }
  if (m.hoilcd_version != SimulatorVersion()) {
    throw InputError(dir, "is a shard rendered by hoilcd " + m.hoilcd_version + " (this is " + SimulatorVersion() +
                              "), whose frames would not match this one's; render every shard with the same hoilcd");
  }
  const IndexRange expected = ContiguousPart(m.shard->shard, m.frame_count);
  if (m.shard->first_frame != expected.begin || m.shard->end_frame != expected.end) {
    throw InputError(dir, "holds " + FramesText(m.shard->first_frame, m.shard->end_frame) + ", but shard " +
                              m.shard->shard.Name() + " of " + std::to_string(m.frame_count) + " frames is " +
                              FramesText(expected.begin, expected.end));
  }
  if (!m.complete) {
    throw InputError(dir, "shard " + m.shard->shard.Name() + " is incomplete (" +
                              FramesText(expected.begin, expected.end) + ", " + std::to_string(m.FramesWritten()) +
                              " written); re-run its hoilcd render command "
                              "to finish it");
  }
  return shard;
}

// Every shard of one render, each once: what the merge is made of (sorted by shard index).
std::vector<ShardFolder> ReadShards(const std::vector<std::string>& dirs) {
  if (dirs.empty()) throw InputError("hoilcd merge", "expected the shard folders to merge");
  std::vector<ShardFolder> shards;
  for (const std::string& dir : dirs) shards.push_back(ReadShard(dir));
  const ShardFolder& first = shards.front();
  const DatasetManifest& a = first.manifest;
  std::map<int, std::string> by_index;
  for (const ShardFolder& shard : shards) {
    const DatasetManifest& b = shard.manifest;
    auto differs = [&](const std::string& what, const std::string& mine, const std::string& theirs) {
      throw InputError(shard.dir, "is a shard of " + what + " " + mine + ", but " + first.dir + " of " + what + " " +
                                      theirs + ": every shard must come from the same render command");
    };
    if (b.scene_hash != a.scene_hash) differs("scene hash", b.scene_hash, a.scene_hash);
    if (b.seed != a.seed) differs("seed", std::to_string(b.seed), std::to_string(a.seed));
    if (b.outputs != a.outputs) differs("--outputs", b.outputs.ToText(), a.outputs.ToText());
    if (b.frame_count != a.frame_count) {
      differs("a sequence of", std::to_string(b.frame_count) + " frames", std::to_string(a.frame_count) + " frames");
    }
    if (b.shard->shard.count != a.shard->shard.count) {
      differs("a render split into", std::to_string(b.shard->shard.count) + " shards",
              std::to_string(a.shard->shard.count) + " shards");
    }
    const auto [at, inserted] = by_index.emplace(b.shard->shard.index, shard.dir);
    if (!inserted)
      throw InputError(shard.dir, "repeats shard " + b.shard->shard.Name() + ", which " + at->second + " holds");
    for (const char* name : kSideFiles) {
      if (Optional(name) && a.files.count(name) == 0 && b.files.count(name) == 0) continue;
      if (a.files.count(name) == 0 || b.files.count(name) == 0 || b.files.at(name) != a.files.at(name)) {
        throw InputError(shard.dir + "/" + name, std::string("differs from ") + first.dir + "/" + name +
                                                     ": every shard of one render writes the same");
      }
    }
  }
  const int count = a.shard->shard.count;
  for (int index = 0; index < count; ++index) {
    if (by_index.count(index) == 0) {
      const IndexRange range = ContiguousPart(Shard{index, count}, a.frame_count);
      throw InputError("hoilcd merge", "shard " + Shard{index, count}.Name() + " (" +
                                           FramesText(range.begin, range.end) +
                                           ") is missing: none of the folders given holds it");
    }
  }
  std::sort(shards.begin(), shards.end(),
            [](const ShardFolder& x, const ShardFolder& y) { return x.part().shard.index < y.part().shard.index; });
  return shards;
}

// The output folder may be new, empty, or hold an earlier dataset of the same render (merged or
// rendered whole): the rules of a render's folder.
void CheckOutputFolder(const std::string& dir, const DatasetManifest& merged) {
  const std::string path = dir + "/manifest.json";
  std::error_code ec;
  if (fs::exists(path, ec)) {
    const DatasetManifest old = DatasetManifest::FromJson(ReadFileBytes(path), path);
    if (old.shard) {
      throw InputError(dir, "holds shard " + old.shard->shard.Name() + ", not a dataset; choose another output folder");
    }
    if (old.frame_count != merged.frame_count) {
      throw InputError(dir, "holds a dataset of " + std::to_string(old.frame_count) +
                                " frames, but the shards are of " + std::to_string(merged.frame_count) +
                                "; choose another output folder or delete this one");
    }
    if (old.hoilcd_version != merged.hoilcd_version || old.scene_hash != merged.scene_hash || old.seed != merged.seed ||
        old.outputs != merged.outputs) {
      throw InputError(dir, "holds a dataset of another scene, seed, simulator version or --outputs (scene hash " +
                                old.scene_hash + ", seed " + std::to_string(old.seed) + ", hoilcd " +
                                old.hoilcd_version + ", --outputs " + old.outputs.ToText() +
                                "); choose another output folder or delete this one");
    }
  } else if (const std::vector<std::string> files = NonTempFiles(dir); !files.empty()) {
    throw InputError(dir,
                     "exists, is not empty and is not a hoilcd dataset (it holds " + JoinFileList(files) +
                         " and no manifest.json); refusing to overwrite files in it: choose a new or empty folder");
  }
}

// DIR/relative's bytes, checked against the shard's manifest.
std::string VerifiedBytes(const ShardFolder& shard, const std::string& relative) {
  const std::string path = shard.dir + "/" + relative;
  const auto listed = shard.manifest.files.find(relative);
  if (listed == shard.manifest.files.end()) {
    throw InputError(shard.dir, "lists no " + relative + " in its manifest.json; re-run its hoilcd render command");
  }
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw InputError(path, "listed in manifest.json but missing; re-run its hoilcd render command");
  std::string bytes = ReadFileBytes(path);
  if (ChecksumOf(bytes) != listed->second) {
    throw InputError(path, "does not match its checksum in manifest.json (damaged); re-run its hoilcd render command");
  }
  return bytes;
}

// The shard's DIR/relative placed at `target` atomically, after checking it against the shard's
// checksum: hard-linked when both folders are on one file system (a dataset file is never changed
// in place, only replaced by a rename, so the two names keep the same bytes), else copied. True
// when linked: its bytes are durable already (the shard synced them), only its folder needs a sync.
bool PlaceFile(const ShardFolder& shard, const std::string& relative, const std::string& target) {
  const std::string source = shard.dir + "/" + relative;
  const auto listed = shard.manifest.files.find(relative);
  if (listed == shard.manifest.files.end()) {
    throw InputError(shard.dir, "lists no " + relative + " in its manifest.json; re-run its hoilcd render command");
  }
  std::error_code ec;
  if (!fs::is_regular_file(source, ec)) {
    throw InputError(source, "listed in manifest.json but missing; re-run its hoilcd render command");
  }
  if (ChecksumOfFile(source) != listed->second) {
    throw InputError(source,
                     "does not match its checksum in manifest.json (damaged); re-run its hoilcd render command");
  }
  // Placed already (a merge re-run into its own output, or one killed after this file): rename(2)
  // of two names of one file does nothing, so a link made now would be left behind as a temp file.
  if (fs::equivalent(source, target, ec)) return true;
  const std::string tmp = target + ".tmp." + std::to_string(::getpid());  // a temp name a re-run removes
  fs::create_directories(fs::path(target).parent_path(), ec);
  fs::remove(tmp, ec);
  fs::create_hard_link(source, tmp, ec);
  if (ec) {
    WriteFileAtomicUnsynced(target, VerifiedBytes(shard, relative));
    return false;
  }
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp);
    throw InputError(target, "cannot rename temporary file into place: " + ec.message());
  }
  return true;
}

// The merged dataset's manifest as it starts: the first shard's, for the whole sequence, no files yet.
DatasetManifest MergedManifest(const DatasetManifest& first) {
  DatasetManifest merged = first;
  merged.shard.reset();
  merged.files.clear();
  merged.complete = false;
  return merged;
}

// Every shard's frame files placed in the output folder in parallel, synced as one batch, then
// listed in the merged manifest.
void PlaceFrameFiles(const std::vector<ShardFolder>& shards, const std::string& output_dir, int threads,
                     DatasetManifest* merged) {
  std::vector<std::pair<const ShardFolder*, std::string>> copies;  // shard, relative path
  for (const ShardFolder& shard : shards) {
    for (int f = shard.part().first_frame; f < shard.part().end_frame; ++f) {
      if (merged->outputs.thermal) copies.emplace_back(&shard, "thermal/" + FrameFileName(f, "png"));
      if (merged->outputs.radiometric) copies.emplace_back(&shard, "radiometric/" + FrameFileName(f, "png"));
      if (merged->outputs.exr) copies.emplace_back(&shard, "exr/" + FrameFileName(f, "exr"));
    }
  }
  ProgressReporter progress("merge", static_cast<int64_t>(copies.size()), "files");
  std::vector<std::string> paths(copies.size());
  std::vector<char> linked(copies.size());
  ParallelFor(static_cast<int64_t>(copies.size()), threads, [&](int64_t i) {
    const auto& [shard, relative] = copies[static_cast<size_t>(i)];
    paths[static_cast<size_t>(i)] = output_dir + "/" + relative;
    linked[static_cast<size_t>(i)] = PlaceFile(*shard, relative, paths[static_cast<size_t>(i)]);
    progress.Update();
  });
  // Copies are synced, links only through their folders (one journal commit, not one per file).
  std::vector<std::string> to_sync;
  for (size_t i = 0; i < paths.size(); ++i) {
    if (!linked[i]) to_sync.push_back(paths[i]);
  }
  std::error_code ec;
  for (const char* folder : {"thermal", "radiometric", "exr"}) {
    if (fs::is_directory(output_dir + "/" + folder, ec)) to_sync.push_back(output_dir + "/" + folder);
  }
  SyncFiles(to_sync);
  for (const auto& [shard, relative] : copies) merged->files[relative] = shard->manifest.files.at(relative);
  progress.Done();
}

// The shards' persons.json joined, each checked to hold its frames, one entry a frame in order.
std::vector<FramePersons> MergedPersons(const std::vector<ShardFolder>& shards, int threads) {
  std::vector<FramePersons> persons;
  for (const ShardFolder& shard : shards) {
    const std::string path = shard.dir + "/persons.json";
    const std::vector<FramePersons> part = PersonsFromJson(VerifiedBytes(shard, "persons.json"), path, threads);
    bool in_order = part.size() == static_cast<size_t>(shard.part().end_frame - shard.part().first_frame);
    for (size_t k = 0; k < part.size() && in_order; ++k) {
      in_order = part[k].frame == shard.part().first_frame + static_cast<int>(k);
    }
    if (!in_order) {
      throw InputError(path, "expected the persons of " + FramesText(shard.part().first_frame, shard.part().end_frame) +
                                 ", one entry a frame in order");
    }
    persons.insert(persons.end(), part.begin(), part.end());
  }
  return persons;
}

// The video files, encoded from the copied, checked frames as a resumed render encodes from its
// folder (the thermal PNGs of a shard are uncompressed even in video mode); returns the seconds taken.
double EncodeMergedVideo(const VideoOptions& video, const std::string& output_dir, int threads,
                         DatasetManifest* merged) {
  const auto start = std::chrono::steady_clock::now();
  const std::string mp4 = EncodeVideo(video, *merged, merged->frame_count, [&](int f) {
    return UncompressedFrame(output_dir, f, *merged, !merged->outputs.thermal);
  });
  WriteVideoFiles(output_dir, mp4, video, merged->frame_count, threads, merged);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The whole sequence's side files, copied from the first shard after checking them.
void CopySideFiles(const ShardFolder& first, const std::string& output_dir, DatasetManifest* merged) {
  for (const char* name : kSideFiles) {
    if (Optional(name) && first.manifest.files.count(name) == 0) continue;
    WriteDatasetFile(output_dir, name, VerifiedBytes(first, name), merged);
  }
}

}  // namespace

MergeResult MergeShards(const std::vector<std::string>& shard_dirs, const std::string& output_dir, int threads) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<ShardFolder> shards = ReadShards(shard_dirs);
  DatasetManifest merged = MergedManifest(shards.front().manifest);
  // One merge at a time into a folder (a render's rule): the second is refused by name.
  const FolderLock lock(output_dir, FolderLock::IfBusy::kRefuse);
  CheckOutputFolder(output_dir, merged);
  const std::string scene_path = shards.front().dir + "/scene.json";
  const Scene scene = SceneFromJson(nlohmann::json::parse(VerifiedBytes(shards.front(), "scene.json")), scene_path);
  const VideoOptions video = scene.camera.video;
  const bool encode_video = merged.outputs.video || (video.enabled && merged.outputs.thermal);

  RemoveDatasetTempFiles(output_dir);
  // First, so a merge stopped half way leaves a folder a re-run recognises as its own.
  WriteFileAtomic(output_dir + "/manifest.json", merged.ToJson());
  PlaceFrameFiles(shards, output_dir, threads, &merged);
  if (merged.outputs.persons) {
    WriteDatasetFile(output_dir, "persons.json", PersonsToJson(MergedPersons(shards, threads), threads), &merged);
  }
  MergeResult result;
  if (encode_video) result.video_seconds = EncodeMergedVideo(video, output_dir, threads, &merged);
  CopySideFiles(shards.front(), output_dir, &merged);
  merged.complete = true;
  WriteFileAtomic(output_dir + "/manifest.json", merged.ToJson());
  result.frames = merged.frame_count;
  result.shards = static_cast<int>(shards.size());
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace hoilcd
