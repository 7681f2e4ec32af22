// Fuzzes the glTF loader (tinygltf plus hoilcd's accessor bounds, node graph and thermal
// extras). Only InputError may come out; a crash, hang or sanitizer report is a bug.
#include <cstddef>
#include <cstdint>

#include "fuzz_input.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/sim/assets/asset.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = hoilcd::fuzz::WriteScratchFile("input.gltf", data, size);
  try {
    hoilcd::LoadAsset(path);
  } catch (const hoilcd::InputError&) {
  }
  return 0;
}
