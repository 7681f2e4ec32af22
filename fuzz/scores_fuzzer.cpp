// Fuzzes the scores file readers of `hoilcd evaluate`. The first byte picks the reader (even: CSV,
// odd: .npy) and the matrix size (1..8 frames); the rest is the file. Only InputError may come
// out; anything else is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "hoilcd/bench/evaluation/scores_file.h"
#include "hoilcd/core/util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  const int frames = 1 + (data[0] >> 1) % 8;
  try {
    if (data[0] % 2 == 0) {
      hoilcd::ScoresFromCsv(bytes, "scores.csv", frames);
    } else {
      hoilcd::ScoresFromNpy(bytes, "scores.npy", frames);
    }
  } catch (const hoilcd::InputError&) {
  }
  return 0;
}
