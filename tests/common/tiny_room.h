// The bench tests' small dataset: tests/data/tiny_room.json (with optional --set overrides)
// rendered into a folder of the test's own, and opened.
#pragma once

#include <string>
#include <vector>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/sim/output/sequence.h"
#include "hoilcd/sim/scene/scene.h"

namespace hoilcd::test {

// Renders the tiny room into `dir`; returns `dir`.
inline std::string RenderTinyRoom(const std::string& dir, const std::vector<std::string>& overrides = {}) {
  const Scene scene = LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/tests/data/tiny_room.json", overrides);
  SequenceOptions options;
  options.output_dir = dir;
  RenderSequence(scene, options);
  return dir;
}

inline Dataset TinyRoomDataset(const std::string& dir, const std::vector<std::string>& overrides = {}) {
  return Dataset::Open(RenderTinyRoom(dir, overrides));
}

}  // namespace hoilcd::test
