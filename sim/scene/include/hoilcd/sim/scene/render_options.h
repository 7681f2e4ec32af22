// What the renderer may do per pixel (edge supersampling, specular reflections) and on how many
// threads; its own header so the typed Scene can hold it without the renderer.
#pragma once

#include <string>

#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

struct RenderOptions {
  bool edge_supersampling;    // supersample pixels on object/material/depth edges
  int edge_samples_per_axis;  // n×n stratified samples in an edge pixel
  bool specular_reflections;  // one traced reflection on specular surfaces
  int threads;                // 0 = the CPUs this process may use (not a scene value)

  RenderOptions();  // the registered defaults
  // Every field once: JSON name (the scene's /camera), unit, default, range, description.
  static const OptionTable<RenderOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

}  // namespace hoilcd
