#include "hoilcd/bench/methods/front_end_input.h"

#include <nlohmann/json.hpp>

namespace hoilcd {

bool IsVideoMode(const Dataset& dataset) {
  const nlohmann::json scene = nlohmann::json::parse(dataset.scene_json(), nullptr, false);
  const nlohmann::json::json_pointer enabled("/camera/video/enabled");
  return !scene.is_discarded() && scene.contains(enabled) && scene[enabled].is_boolean() &&
         scene[enabled].get<bool>();
}

FrontEndInput ReadFrontEndInput(const Dataset& dataset, int frame, bool video_mode, bool detector) {
  FrontEndInput input;
  input.thermal_u8 = dataset.Thermal(frame);
  if (detector && !video_mode) input.radiometric_c = dataset.RadiometricC(frame);
  return input;
}

}  // namespace hoilcd
