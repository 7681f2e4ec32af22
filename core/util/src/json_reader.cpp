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
  size_t index = 0;  // an array's current element
  std::string key;   // an object's current key
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

// nlohmann's document builder with the checks in front of it. (nlohmann's callback parser would
// do, but it searches the parent for discarded values at every object's end: quadratic in a list
// of objects.)
class CheckingBuilder {
 public:
  using json = nlohmann::json;
  CheckingBuilder(json* result, const std::string& source) : dom_(*result), source_(source) {}

  bool null() { return Value(dom_.null()); }
  bool boolean(bool value) { return Value(dom_.boolean(value)); }
  bool number_integer(json::number_integer_t value) { return Value(dom_.number_integer(value)); }
  bool number_unsigned(json::number_unsigned_t value) { return Value(dom_.number_unsigned(value)); }
  bool number_float(json::number_float_t value, const json::string_t& text) {
    return Value(dom_.number_float(value, text));
  }
  bool string(json::string_t& value) { return Value(dom_.string(value)); }
  bool binary(json::binary_t& value) { return Value(dom_.binary(value)); }
  bool start_object(std::size_t size) { return Open(false) && dom_.start_object(size); }
  bool start_array(std::size_t size) { return Open(true) && dom_.start_array(size); }
  bool end_object() { return Close() && dom_.end_object(); }
  bool end_array() { return Close() && dom_.end_array(); }
  bool key(json::string_t& key) {
    OpenValue& object = open_.back();
    object.key = key;
    if (!object.keys.insert(key).second) {
      throw InputError(source_ + ": " + PointerOf(open_),
                       "the key \"" + SafeText(key) + "\" is repeated in one object; expected each key once");
    }
    return dom_.key(key);
  }
  template <class Exception>
  bool parse_error(std::size_t position, const std::string& token, const Exception& error) {
    return dom_.parse_error(position, token, error);  // throws `error`
  }

 private:
  // An element of the innermost array ended: the next one has the next index.
  bool Value(bool kept) {
    if (!open_.empty() && open_.back().array) ++open_.back().index;
    return kept;
  }
  bool Open(bool array) {
    if (open_.size() >= static_cast<size_t>(kMaxJsonDepth)) {
      throw InputError(source_ + ": " + PointerOf(open_),
                       "nests deeper than " + std::to_string(kMaxJsonDepth) + " levels of objects and arrays");
    }
    open_.push_back({array, 0, {}, {}});
    return true;
  }
  bool Close() {
    open_.pop_back();
    return Value(true);
  }

  nlohmann::detail::json_sax_dom_parser<json> dom_;
  const std::string& source_;
  std::vector<OpenValue> open_;
};

}  // namespace

JsonSyntaxError::JsonSyntaxError(const std::string& source, std::string detail)
    : InputError(source, "invalid JSON (" + detail + ")"), detail_(std::move(detail)) {}

nlohmann::json ParseJson(std::string_view text, const std::string& source) {
  nlohmann::json document;
  CheckingBuilder builder(&document, source);
  try {
    nlohmann::json::sax_parse(text, &builder);
  } catch (const nlohmann::json::exception& e) {  // parse errors and number overflow (1e400)
    throw JsonSyntaxError(source, Detail(e));
  }
  return document;
}

nlohmann::json ParseJsonOrDiscarded(std::string_view text) {
  try {
    return ParseJson(text, "");
  } catch (const InputError&) {
    return nlohmann::json(nlohmann::json::value_t::discarded);
  }
}

}  // namespace hoilcd
