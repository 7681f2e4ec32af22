#include "hoilcd/bench/methods/manifest_options.h"

namespace hoilcd {

BenchOptions WithManifest(BenchOptions options, const DatasetManifest& manifest) {
  options.detector.u8_min_c = manifest.window_min_c;
  options.detector.u8_max_c = manifest.window_max_c;
  options.tracker.frame_rate_hz = manifest.frame_rate_hz;
  return options;
}

}  // namespace hoilcd
