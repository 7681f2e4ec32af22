// Fuzzes the real-frame reader of `hoilcd realism`. The first byte picks the file's extension
// (bits 0-1: .npy, .png, .tif, .jpg; .jpg reaches the FLIR radiometric JPEG reader, whose seeds
// start with byte 3) and the reading options (bit 2: a centikelvin scale and offset or none;
// bits 3-4: float unit auto, c, k); the rest is the file. Only InputError may come out; anything
// else is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_input.h"
#include "hoilcd/bench/realism/real_frames.h"
#include "hoilcd/core/util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  static const char* const kNames[] = {"frame.npy", "frame.png", "frame.tif", "frame.jpg"};
  static const char* const kUnits[] = {"auto", "c", "k", "auto"};
  hoilcd::RealFrameOptions options;
  if (data[0] & 4) {
    options.scale = 0.01;
    options.offset_c = -273.15;
  }
  options.float_unit = kUnits[(data[0] >> 3) % 4];
  try {
    hoilcd::ReadRealFrame(hoilcd::fuzz::WriteScratchFile(kNames[data[0] % 4], data + 1, size - 1), options);
  } catch (const hoilcd::InputError&) {
  }
  return 0;
}
