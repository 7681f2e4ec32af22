#include "hoilcd/core/util/json_reader.h"

#include <set>
#include <vector>

#include "hoilcd/core/util/safe_text.h"
#include "hoilcd/core/util/sizes.h"

namespace hoilcd {
namespace {

// One open object or array while parsing: where its current element is, and an object's keys.
struct OpenValue {
  bool array = false;
  size_t index = 0;       // an array's current element
  std::string key;        // an object's current key
  std::set<std::string> keys;
};

// "/a/0/b": the pointer of the element each open value is at.
std::string PointerOf(const std::vector<OpenValue>& open) {
  std::string pointer;
  for (const OpenValue& v : open) pointer += "/" + (v.array ? std::to_string(v.index) : JsonPointerToken(v.key));
  return pointer.empty() ? "/" : SafeText(pointer);
}

// nlohmann's message without its "[json.exception.parse_error.101] " prefix.
std::string Detail(const nlohmann::json::exception& e) {
  std::string what = e.what();
  const size_t end = what.find("] ");
  if (what.rfind("[json.exception.", 0) == 0 && end != std::string::npos) what = what.substr(end + 2);
  return what;
}

}  // namespace

JsonSyntaxError::JsonSyntaxError(const std::string& source, std::string detail)
    : InputError(source, "invalid JSON (" + detail + ")"), detail_(std::move(detail)) {}

nlohmann::json ParseJson(std::string_view text, const std::string& source) {
  std::vector<OpenValue> open;
  // An element of the innermost array ended: the next one has the next index.
  const auto element_done = [&open] {
    if (!open.empty() && open.back().array) ++open.back().index;
  };
  const auto check = [&](int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using Event = nlohmann::json::parse_event_t;
    switch (event) {
      case Event::object_start:
      case Event::array_start:
        if (open.size() >= static_cast<size_t>(kMaxJsonDepth)) {
          throw InputError(source + ": " + PointerOf(open),
                           "nests deeper than " + std::to_string(kMaxJsonDepth) + " levels of objects and arrays");
        }
        open.push_back({event == Event::array_start, 0, {}, {}});
        break;
      case Event::key: {
        OpenValue& object = open.back();
        object.key = parsed.get<std::string>();
        if (!object.keys.insert(object.key).second) {
          throw InputError(source + ": " + PointerOf(open), "the key \"" + SafeText(object.key) +
                                                                "\" is repeated in one object; expected each key once");
        }
        break;
      }
      case Event::object_end:
      case Event::array_end:
        open.pop_back();
        element_done();
        break;
      case Event::value: element_done(); break;
    }
    return true;
  };
  try {
    return nlohmann::json::parse(text, check);
  } catch (const nlohmann::json::exception& e) {  // parse errors and number overflow (1e400)
    throw JsonSyntaxError(source, Detail(e));
  }
}

nlohmann::json ParseJsonOrDiscarded(std::string_view text) {
  try {
    return ParseJson(text, "");
  } catch (const InputError&) {
    return nlohmann::json(nlohmann::json::value_t::discarded);
  }
}

}  // namespace hoilcd
