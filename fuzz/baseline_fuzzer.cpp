// Fuzzes the CI gate's baseline reader (`--baseline REPORT.json`): the input is the report's
// text. Only InputError may come out; anything else is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "hoilcd/bench/evaluation/report_json.h"
#include "hoilcd/core/util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    hoilcd::ReportJsonFromText(std::string_view(reinterpret_cast<const char*>(data), size), "baseline.json");
  } catch (const hoilcd::InputError&) {
  }
  return 0;
}
