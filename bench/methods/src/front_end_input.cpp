#include "hoilcd/bench/methods/front_end_input.h"

#include <nlohmann/json.hpp>

#include "hoilcd/core/dataset/exr_io.h"
#include "hoilcd/core/dataset/frame_encoding.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/json_reader.h"

namespace hoilcd {

bool IsVideoMode(const Dataset& dataset) {
  const nlohmann::json scene = ParseJsonOrDiscarded(dataset.scene_json());
  const nlohmann::json::json_pointer enabled("/camera/video/enabled");
  return !scene.is_discarded() && scene.contains(enabled) && scene[enabled].is_boolean() && scene[enabled].get<bool>();
}

FrontEndInput ReadFrontEndInput(const Dataset& dataset, int frame, bool video_mode, bool detector) {
  FrontEndInput input;
  input.thermal_u8 = dataset.Thermal(frame);
  if (detector && !video_mode) input.radiometric_c = dataset.RadiometricC(frame);
  return input;
}

GroundTruthInput ReadGroundTruthInput(const Dataset& dataset, int frame, bool ideal, bool persons) {
  GroundTruthInput input;
  if (!ideal && !persons) return input;
  const DatasetManifest& manifest = dataset.manifest();
  const int person = manifest.ClassId("person");
  if (persons && person == DatasetManifest::kNoClass) {
    throw InputError(dataset.dir() + "/manifest.json", "no \"person\" in /classes, which the true person masks need");
  }
  for (const auto& [name, channel] : ReadDatasetExr(dataset, frame)) {
    if (ideal && name == "T_true")
      input.ideal_u8 = ToDisplay8Bit(channel, manifest.window_min_c, manifest.window_max_c);
    if (persons && name == "class") input.person_mask = channel == static_cast<float>(person);
  }
  const std::string path = DatasetExrPath(dataset, frame);
  if (ideal && input.ideal_u8.empty()) throw InputError(path, "no T_true channel (the true temperature)");
  if (persons && input.person_mask.empty()) throw InputError(path, "no class channel (the person masks)");
  return input;
}

std::vector<Track> GroundTruthTracks(const FramePersons& frame) {
  std::vector<Track> tracks;
  for (const PersonRecord& p : frame.persons) {
    if (p.visible_fraction <= 0) continue;  // hidden: its box is where it would be, not a pixel of it
    Track t;
    t.id = p.id;
    t.box = p.box_px;
    t.score = 1;
    tracks.push_back(t);
  }
  return tracks;
}

}  // namespace hoilcd
