// Fuzzes ParseJson, the one JSON entry point of every reader: any text gives a document or an
// InputError (nesting bounded, repeated keys refused), and a document it gives parses again, from
// its own dump, to the same document. Anything else (or a sanitizer report) is a bug.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/json_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  nlohmann::json doc;
  try {
    doc = hoilcd::ParseJson(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.json");
  } catch (const hoilcd::InputError&) {
    return 0;
  }
  if (hoilcd::ParseJson(doc.dump(), "dump.json") != doc) std::abort();
  return 0;
}
