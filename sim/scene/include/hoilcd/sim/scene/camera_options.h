// The scene's camera as one typed object (the scene's /camera): image size and field of view,
// the sensor model's effects, what the renderer does per pixel, and the thermal.mp4 encoding.
#pragma once

#include "hoilcd/core/dataset/video.h"
#include "hoilcd/core/util/option_table.h"
#include "hoilcd/sim/scene/render_options.h"
#include "hoilcd/sim/sensor/sensor.h"

namespace hoilcd {

struct CameraOptions {
  int width_px;          // image width, px
  int height_px;         // image height, px
  double hfov_deg;       // horizontal field of view, deg
  SensorOptions sensor;  // its fields sit in /camera itself
  RenderOptions render;  // its fields sit in /camera itself
  VideoOptions video;    // /camera/video

  CameraOptions();  // the registered defaults
  // Every field once (the sensor's and renderer's tables flattened in, the video's nested).
  static const OptionTable<CameraOptions>& Table();
};

}  // namespace hoilcd
