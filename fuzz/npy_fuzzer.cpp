// Fuzzes the .npy scores reader of `hoilcd evaluate`. The first byte picks the matrix size (1..8
// frames, bits 1-3) and the way in (bit 0: 0 the bytes, ScoresFromNpy; 1 a file, ReadScoresFile,
// which reads the header, checks the size against it, then the body); the rest is the file. Only
// InputError may come out; anything else is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_input.h"
#include "hoilcd/bench/evaluation/scores_file.h"
#include "hoilcd/core/util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const int frames = 1 + (data[0] >> 1) % 8;
  try {
    if (data[0] % 2 == 0) {
      hoilcd::ScoresFromNpy(std::string(reinterpret_cast<const char*>(data) + 1, size - 1), "scores.npy", frames);
    } else {
      hoilcd::ReadScoresFile(hoilcd::fuzz::WriteScratchFile("scores.npy", data + 1, size - 1), frames);
    }
  } catch (const hoilcd::InputError&) {
  }
  return 0;
}
