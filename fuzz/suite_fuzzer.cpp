// Fuzzes the suite file parser (`hoilcd suite SUITE`): the input is the file's text. Only
// InputError may come out; anything else is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "hoilcd/bench/pipeline/suite_file.h"
#include "hoilcd/core/util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const hoilcd::Suite suite =
        hoilcd::ParseSuite(std::string(reinterpret_cast<const char*>(data), size), "suite.json");
    hoilcd::SuiteRuns(suite, "all");
  } catch (const hoilcd::InputError&) {
  }
  return 0;
}
