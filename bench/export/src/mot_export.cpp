#include "hoilcd/bench/export/mot_export.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <set>
#include <sstream>

#include "hoilcd/bench/methods/front_ends.h"
#include "hoilcd/bench/methods/manifest_options.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/file_io.h"
#include "hoilcd/core/util/folder_lock.h"
#include "hoilcd/core/util/json_reader.h"

namespace hoilcd {
namespace {

constexpr const char* kBenchmark = "HOILCD-train";

std::string Box(const cv::Rect2f& b) {
  char buf[96];
  std::snprintf(buf, sizeof(buf), "%.2f,%.2f,%.2f,%.2f", b.x + 1.0, b.y + 1.0, b.width, b.height);  // 1-based pixels
  return buf;
}

}  // namespace

std::string MotGroundTruth(const std::vector<FramePersons>& persons, const TrackingMetricsOptions& options) {
  std::string out;
  char tail[64];
  for (const FramePersons& f : persons) {
    for (const PersonRecord& p : f.persons) {
      const bool scored =
          p.visible_fraction >= options.min_visible_fraction && p.box_px.height >= options.min_box_height_px;
      std::snprintf(tail, sizeof(tail), ",%d,%d,%.4f\n", scored ? 1 : 0, scored ? 1 : 8, p.visible_fraction);
      out += std::to_string(f.frame + 1) + "," + std::to_string(p.id + 1) + "," + Box(p.box_px) + tail;
    }
  }
  return out;
}

std::string MotTracks(const std::vector<FrameTracks>& tracks) {
  std::string out;
  for (const FrameTracks& f : tracks) {
    for (const TrackedBox& t : f.tracks) {
      out += std::to_string(f.frame + 1) + "," + std::to_string(t.id) + "," + Box(t.box) + ",1,-1,-1,-1\n";
    }
  }
  return out;
}

std::string MotSequenceName(const Dataset& dataset) {
  const nlohmann::json scene = ParseJsonOrDiscarded(dataset.scene_json());
  const bool named = scene.is_object() && scene.contains("name") && scene["name"].is_string();
  const DatasetManifest& m = dataset.manifest();
  const std::string& hash = m.scene_hash;
  const std::string hash_hex = hash.substr(hash.find(':') == std::string::npos ? 0 : hash.find(':') + 1, 8);
  std::string sequence = "HOILCD-" + (named ? scene["name"].get<std::string>() : std::string("scene")) + "-seed" +
                         std::to_string(m.seed) + "-" + hash_hex;
  for (char& c : sequence)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-') c = '_';
  return sequence;
}

namespace {

// The seqmap at `path` (absent: none yet) with `sequence` added: "name" then the sequences, sorted.
std::string SeqmapWith(const std::string& path, const std::string& sequence) {
  std::set<std::string> sequences = {sequence};
  std::error_code ec;
  if (std::filesystem::exists(path, ec)) {
    std::istringstream in(ReadFileBytes(path));
    std::string line;
    if (!std::getline(in, line) || line != "name") {
      throw InputError(path, "expected a MOTChallenge seqmap (first line \"name\") to add the sequence to");
    }
    while (std::getline(in, line)) {
      if (!line.empty()) sequences.insert(line);
    }
  }
  std::string out = "name\n";
  for (const std::string& s : sequences) out += s + "\n";
  return out;
}

}  // namespace

MotExport ExportMot(const Dataset& dataset, const BenchOptions& options_in, const std::string& out_dir) {
  const BenchOptions options = WithManifest(options_in, dataset.manifest());
  FrontEndOptions front;
  front.detector = options.detector;
  front.tracker = options.tracker;
  front.hoi = options.hoi;
  front.threads = options.threads;
  const FrontEndOutput out = RunFrontEnds(dataset, {FrontEnd::kPersons}, front);

  const std::string sequence = MotSequenceName(dataset);
  const DatasetManifest& m = dataset.manifest();
  const std::string gt_root = out_dir + "/gt/mot_challenge";
  const std::string seq_dir = gt_root + "/" + kBenchmark + "/" + sequence;
  // Exports of several datasets into one folder share its seqmap, read, added to and written back:
  // one process at a time, or one of two sequences exported at once would be lost from it.
  const FolderLock lock(out_dir, FolderLock::IfBusy::kWait);
  MotExport e;
  e.sequence = sequence;
  e.ground_truth = seq_dir + "/gt/gt.txt";
  e.tracks = out_dir + "/trackers/mot_challenge/" + kBenchmark + "/hoilcd-dlcd/data/" + sequence + ".txt";
  WriteFileAtomic(e.ground_truth, MotGroundTruth(dataset.persons(), options.tracking_metrics));
  char info[512];
  std::snprintf(info, sizeof(info),
                "[Sequence]\nname=%s\nimDir=img1\nframeRate=%g\nseqLength=%d\nimWidth=%d\nimHeight=%d\nimExt=.png\n",
                sequence.c_str(), m.frame_rate_hz, dataset.num_frames(), m.intrinsics.width, m.intrinsics.height);
  WriteFileAtomic(seq_dir + "/seqinfo.ini", info);
  const std::string seqmap = gt_root + "/seqmaps/" + kBenchmark + ".txt";
  WriteFileAtomic(seqmap, SeqmapWith(seqmap, sequence));
  WriteFileAtomic(e.tracks, MotTracks(out.tracks));
  return e;
}

}  // namespace hoilcd
