// The one way hoilcd parses the JSON it reads (ParseJson: nesting bounded, repeated keys refused),
// and reading typed fields from it, every problem collected with its file and JSON pointer
// ("FILE: /json/pointer") in a ProblemCollector; unknown keys are errors, so typos fail loudly.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>

#include <nlohmann/json.hpp>

#include "hoilcd/core/util/error.h"

namespace hoilcd {

// `key` as one JSON pointer token (RFC 6901: '~' as "~0", '/' as "~1").
inline std::string JsonPointerToken(const std::string& key) {
  std::string out;
  for (char c : key) {
    if (c == '~') {
      out += "~0";
    } else if (c == '/') {
      out += "~1";
    } else {
      out += c;
    }
  }
  return out;
}

// Where b first differs from a, as a JSON pointer (the path of the first operation of their JSON
// Patch); "/" when they are equal.
inline std::string JsonFirstDifference(const nlohmann::json& a, const nlohmann::json& b) {
  const nlohmann::json patch = nlohmann::json::diff(a, b);
  return patch.empty() ? "/" : patch.front().value("path", "/");
}

// Text that is not JSON (a syntax error, or a number beyond a double such as 1e400): what() is
// "SOURCE: invalid JSON (DETAIL)"; a reader with its own wording uses detail().
class JsonSyntaxError : public InputError {
 public:
  JsonSyntaxError(const std::string& source, std::string detail);
  const std::string& detail() const { return detail_; }

 private:
  std::string detail_;
};

// Parses JSON text that `source` (a file, or a flag) holds, for every reader of user input.
// Refuses, each as an InputError("SOURCE: /json/pointer", ...), before the document is built
// further: nesting deeper than kMaxJsonDepth (sizes.h) and a key an object repeats (JSON leaves
// its meaning open; nlohmann would keep the last silently). A syntax error: JsonSyntaxError.
nlohmann::json ParseJson(std::string_view text, const std::string& source);

// ParseJson's document, or a discarded value (is_discarded()) for text it refuses: for files whose
// being unreadable is itself the answer (a cache record, an earlier output's marker).
nlohmann::json ParseJsonOrDiscarded(std::string_view text);

// Reads typed JSON fields and reports each problem as "FILE: /json/pointer".
class JsonReader {
 public:
  explicit JsonReader(std::string path) : path_(std::move(path)) {}

  ProblemCollector& problems() { return problems_; }

  void Add(const std::string& pointer, std::string message) {
    problems_.Add(path_ + ": " + (pointer.empty() ? "/" : pointer), std::move(message));
  }

  nlohmann::json Parse(std::string_view text) { return ParseJson(text, path_); }

  bool ExpectObject(const nlohmann::json& value, const std::string& pointer) {
    if (value.is_object()) return true;
    Add(pointer, "expected an object");
    return false;
  }

  bool ExpectArray(const nlohmann::json& value, const std::string& pointer) {
    if (value.is_array()) return true;
    Add(pointer, "expected an array");
    return false;
  }

  // Unknown keys are errors, so typos fail loudly.
  void CheckKeys(const nlohmann::json& object, const std::string& pointer, std::initializer_list<const char*> allowed) {
    for (const auto& item : object.items()) {
      bool known = false;
      for (const char* key : allowed) known = known || item.key() == key;
      if (!known) Add(pointer + "/" + item.key(), "unknown key");
    }
  }

  template <typename T>
  void Read(const nlohmann::json& object, const std::string& pointer, const char* key, T* out) {
    const std::string where = pointer + "/" + key;
    const auto it = object.find(key);
    if (it == object.end()) {
      Add(where, "missing");
      return;
    }
    ReadValue(*it, where, out);
  }

  void ReadValue(const nlohmann::json& value, const std::string& where, std::string* out) {
    if (value.is_string())
      *out = value.get<std::string>();
    else
      Add(where, "expected a string");
  }
  void ReadValue(const nlohmann::json& value, const std::string& where, double* out) {
    if (value.is_number())
      *out = value.get<double>();
    else
      Add(where, "expected a number");
  }
  void ReadValue(const nlohmann::json& value, const std::string& where, float* out) {
    if (value.is_number())
      *out = value.get<float>();
    else
      Add(where, "expected a number");
  }
  void ReadValue(const nlohmann::json& value, const std::string& where, int* out) {
    if (value.is_number_integer() && value.get<int64_t>() >= INT32_MIN && value.get<int64_t>() <= INT32_MAX) {
      *out = value.get<int>();
    } else {
      Add(where, "expected a 32-bit integer");
    }
  }
  void ReadValue(const nlohmann::json& value, const std::string& where, uint64_t* out) {
    if (value.is_number_unsigned())
      *out = value.get<uint64_t>();
    else
      Add(where, "expected a non-negative integer");
  }
  void ReadValue(const nlohmann::json& value, const std::string& where, bool* out) {
    if (value.is_boolean())
      *out = value.get<bool>();
    else
      Add(where, "expected true or false");
  }

 private:
  std::string path_;
  ProblemCollector problems_;
};

}  // namespace hoilcd
