// Fuzzes the scene loader: JSON parsing (ParseJson, as LoadScene), the schema validator, required properties, the
// cross-field checks and --set overrides. Input: optional leading lines "--set KEY=VALUE", then
// the scene JSON. Only InputError may come out; anything else (or a sanitizer report) is a bug.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/json_reader.h"
#include "hoilcd/sim/scene/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> overrides;
  while (text.rfind("--set ", 0) == 0) {
    const size_t end = text.find('\n');
    overrides.push_back(text.substr(6, end == std::string::npos ? std::string::npos : end - 6));
    text = end == std::string::npos ? "" : text.substr(end + 1);
  }
  try {
    hoilcd::SceneFromJson(hoilcd::ParseJson(text, "fuzz.json"), "fuzz.json", overrides);
  } catch (const hoilcd::InputError&) {
  }
  return 0;
}
