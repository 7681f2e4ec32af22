#include "hoilcd/bench/export/coco_export.h"

#include <filesystem>

#include <nlohmann/json.hpp>

#include "hoilcd/core/dataset/dataset_folder.h"
#include "hoilcd/core/util/error.h"

namespace hoilcd {

namespace {
// COCO's names and limb list (1-based keypoint indices), as in person_keypoints_*.json.
const char* const kNames[17] = {"nose",          "left_eye",       "right_eye",  "left_ear",    "right_ear",
                                "left_shoulder", "right_shoulder", "left_elbow", "right_elbow", "left_wrist",
                                "right_wrist",   "left_hip",       "right_hip",  "left_knee",   "right_knee",
                                "left_ankle",    "right_ankle"};
const int kSkeleton[19][2] = {{16, 14}, {14, 12}, {17, 15}, {15, 13}, {12, 13}, {6, 12}, {7, 13},
                              {6, 7},   {6, 8},   {7, 9},   {8, 10},  {9, 11},  {2, 3},  {1, 2},
                              {1, 3},   {2, 4},   {3, 5},   {4, 6},   {5, 7}};
}  // namespace

std::string CocoKeypointsJson(const Dataset& dataset) {
  using nlohmann::json;
  const DatasetManifest& m = dataset.manifest();
  const int W = m.intrinsics.width, H = m.intrinsics.height;
  // The images the annotations point to must be there (a COCO reader opens them by file_name).
  if (!m.outputs.thermal) {
    throw InputError(dataset.dir(), "has no thermal frames (rendered with --outputs " + m.outputs.ToText() +
                                        "): COCO's images are the thermal PNGs; render with thermal");
  }
  std::vector<std::string> missing;
  for (int f = 0; f < m.frame_count; ++f) {
    const std::string file = "thermal/" + FrameFileName(f, "png");
    std::error_code ec;
    if (!std::filesystem::is_regular_file(dataset.dir() + "/" + file, ec)) missing.push_back(file);
  }
  if (!missing.empty()) {
    throw InputError(dataset.dir(), "the COCO images " + JoinFileList(missing) + " are missing (" +
                                        std::to_string(missing.size()) + " of " + std::to_string(m.frame_count) +
                                        "): restore or re-render the dataset");
  }
  json images = json::array(), annotations = json::array();
  for (int f = 0; f < m.frame_count; ++f) {
    images.push_back({{"id", f}, {"file_name", "thermal/" + FrameFileName(f, "png")}, {"width", W}, {"height", H}});
  }
  int next_id = 1;
  for (const FramePersons& frame : dataset.persons()) {
    for (const PersonRecord& p : frame.persons) {
      if (p.keypoints.size() != 17) {
        throw InputError(dataset.dir() + "/persons.json",
                         "frame " + std::to_string(frame.frame) + ", person " + std::to_string(p.id) +
                             ": expected the 17 COCO keypoints (rendered by hoilcd before they existed? render again)");
      }
      json keypoints = json::array();
      int labelled = 0;
      for (const KeypointRecord& k : p.keypoints) {
        const bool inside = k.u_px >= -0.5 && k.v_px >= -0.5 && k.u_px < W - 0.5 && k.v_px < H - 0.5;
        const int flag = !inside ? 0 : k.visible ? 2 : 1;
        keypoints.push_back(flag ? k.u_px : 0.0);
        keypoints.push_back(flag ? k.v_px : 0.0);
        keypoints.push_back(flag);
        labelled += flag > 0;
      }
      annotations.push_back({{"id", next_id++},
                             {"image_id", frame.frame},
                             {"category_id", 1},
                             {"track_id", p.id},
                             {"keypoints", keypoints},
                             {"num_keypoints", labelled},
                             {"bbox", {p.box_px.x, p.box_px.y, p.box_px.width, p.box_px.height}},
                             {"area", p.box_px.width * p.box_px.height},
                             {"iscrowd", 0}});
    }
  }
  json names = json::array(), limbs = json::array();
  for (const char* n : kNames) names.push_back(n);
  for (const auto& limb : kSkeleton) limbs.push_back({limb[0], limb[1]});
  const json doc = {
      {"info", {{"description", "hoilcd ground truth"}, {"version", m.hoilcd_version}, {"scene_hash", m.scene_hash}}},
      {"images", images},
      {"annotations", annotations},
      {"categories",
       json::array(
           {{{"id", 1}, {"name", "person"}, {"supercategory", "person"}, {"keypoints", names}, {"skeleton", limbs}}})}};
  return doc.dump(1) + "\n";
}

std::string ExportCoco(const std::string& dataset_dir, const std::string& out_dir) {
  const Dataset dataset = Dataset::Open(dataset_dir, Verify::kOnRead);
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) throw InputError(out_dir, "cannot create the output folder (" + ec.message() + ")");
  const std::string path = out_dir + "/person_keypoints.json";
  WriteFileAtomic(path, CocoKeypointsJson(dataset));
  return path;
}

}  // namespace hoilcd
