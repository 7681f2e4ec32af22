// The bench tests' small dataset: tests/data/tiny_room.json (with optional --set overrides)
// rendered into a folder of the test's own, and opened. The render is cached within a ctest run
// (render_cache.h): each test gets a folder of its own, of hard links to the cached files.
#pragma once

#include <string>
#include <vector>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/util/file_io.h"
#include "hoilcd/sim/output/sequence.h"
#include "hoilcd/sim/scene/scene.h"
#include "render_cache.h"

namespace hoilcd::test {

// Renders the tiny room into `dir`; returns `dir`.
inline std::string RenderTinyRoom(const std::string& dir, const std::vector<std::string>& overrides = {}) {
  const std::string file = std::string(HOILCD_TEST_SOURCE_DIR) + "/tests/data/tiny_room.json";
  std::string key = "RenderTinyRoom\n" + ReadFileBytes(file);
  for (const std::string& o : overrides) key += "\n--set " + o;
  CachedRender(key, dir, [&](const std::string& into) {
    SequenceOptions options;
    options.output_dir = into;
    RenderSequence(LoadScene(file, overrides), options);
  });
  return dir;
}

inline Dataset TinyRoomDataset(const std::string& dir, const std::vector<std::string>& overrides = {}) {
  return Dataset::Open(RenderTinyRoom(dir, overrides));
}

}  // namespace hoilcd::test
