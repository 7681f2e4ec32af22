#include "hoilcd/bench/evaluation/npy.h"

#include <charconv>

#include "hoilcd/core/util/safe_text.h"

namespace hoilcd {
namespace {

constexpr size_t kQuoteBytes = 80;  // of a header quoted in a message

std::string Quoted(std::string_view bytes) {
  return "'" + SafeText(bytes.substr(0, kQuoteBytes)) + (bytes.size() > kQuoteBytes ? "...'" : "'");
}

}  // namespace

InputError NpyTruncatedHeader(const std::string& source, size_t needed, size_t held) {
  return InputError(source, "truncated .npy header: expected " + std::to_string(needed) +
                                " bytes up to the header's end, the file holds " + std::to_string(held));
}

NpyPreamble ReadNpyPreamble(std::string_view bytes, const std::string& source) {
  if (bytes.size() < 10 || bytes.substr(0, 6) != std::string_view("\x93NUMPY", 6)) {
    throw InputError(source, "expected a NumPy .npy file (magic \\x93NUMPY)");
  }
  const auto byte = [&](size_t i) { return static_cast<size_t>(static_cast<unsigned char>(bytes[i])); };
  NpyPreamble p;
  const size_t major = byte(6);
  if (major == 1) {
    p.header_bytes = byte(8) | byte(9) << 8;
    p.header_start = 10;
  } else if (major == 2 || major == 3) {
    if (bytes.size() < kNpyPreambleBytes) throw NpyTruncatedHeader(source, kNpyPreambleBytes, bytes.size());
    for (int i = 3; i >= 0; --i) p.header_bytes = p.header_bytes << 8 | byte(8 + static_cast<size_t>(i));
    p.header_start = 12;
  } else {
    throw InputError(source, ".npy format version " + std::to_string(major) + ": expected 1, 2 or 3");
  }
  if (p.header_bytes > kMaxNpyHeaderBytes) {
    throw InputError(source, ".npy header of " + std::to_string(p.header_bytes) + " bytes: expected at most " +
                                 std::to_string(kMaxNpyHeaderBytes) + " (numpy writes ~120)");
  }
  return p;
}

std::map<std::string, std::string> NpyHeaderFields(const std::string& header, const std::string& source) {
  const auto fail = [&](const std::string& what) {
    throw InputError(source, ".npy header " + Quoted(header) + ": " + what);
  };
  size_t i = 0;
  const auto skip_space = [&] {
    while (i < header.size() && (header[i] == ' ' || header[i] == '\n' || header[i] == '\t')) ++i;
  };
  const auto quoted = [&]() -> std::string {  // a Python string literal without escapes
    const char quote = header[i];
    const size_t close = header.find(quote, i + 1);
    if (close == std::string::npos) fail("a string is not closed");
    std::string text = header.substr(i, close + 1 - i);
    i = close + 1;
    return text;
  };
  const auto value = [&]() -> std::string {
    if (i < header.size() && (header[i] == '\'' || header[i] == '"')) return quoted();
    const size_t start = i;
    int depth = 0;  // of (...) and [...]
    while (i < header.size()) {
      const char c = header[i];
      if (c == '\'' || c == '"') {
        quoted();
        continue;
      }
      if (c == '(' || c == '[') ++depth;
      if (c == ')' || c == ']') --depth;
      if (depth < 0 || (depth == 0 && (c == ',' || c == '}'))) break;
      ++i;
    }
    if (depth != 0) fail("its brackets do not match");
    std::string text = header.substr(start, i - start);
    while (!text.empty() && (text.back() == ' ' || text.back() == '\n' || text.back() == '\t')) text.pop_back();
    if (text.empty()) fail("a key has no value");
    return text;
  };
  skip_space();
  if (i == header.size() || header[i] != '{')
    fail("expected a Python dict {'descr': ..., 'fortran_order': ..., 'shape': ...}");
  ++i;
  std::map<std::string, std::string> fields;
  for (;;) {
    skip_space();
    if (i < header.size() && header[i] == '}') break;
    if (i == header.size() || (header[i] != '\'' && header[i] != '"')) fail("expected a quoted key or '}'");
    const std::string quoted_key = quoted();
    const std::string key = quoted_key.substr(1, quoted_key.size() - 2);
    if (key != "descr" && key != "fortran_order" && key != "shape") {
      fail("key " + Quoted(key) + ": expected only 'descr', 'fortran_order' and 'shape'");
    }
    skip_space();
    if (i == header.size() || header[i] != ':') fail("expected ':' after '" + key + "'");
    ++i;
    skip_space();
    if (!fields.emplace(key, value()).second) fail("'" + key + "' is given twice");
    skip_space();
    if (i < header.size() && header[i] == ',') {
      ++i;
    } else if (i == header.size() || header[i] != '}') {
      fail("expected ',' or '}' after the value of '" + key + "'");
    }
  }
  ++i;
  skip_space();
  if (i != header.size()) fail("text after the dict's '}'");
  for (const char* key : {"descr", "fortran_order", "shape"}) {
    if (fields.count(key) == 0) throw InputError(source, ".npy header has no '" + std::string(key) + "'");
  }
  return fields;
}

bool ParseNpyShape(const std::string& text, std::vector<int64_t>* dims) {
  if (text.size() < 2 || text.front() != '(' || text.back() != ')') return false;
  const std::string inside = text.substr(1, text.size() - 2);
  size_t start = 0;
  bool trailing_comma = false;
  while (start < inside.size()) {
    const size_t comma = std::min(inside.find(',', start), inside.size());
    std::string_view item(inside.data() + start, comma - start);
    while (!item.empty() && item.front() == ' ') item.remove_prefix(1);
    while (!item.empty() && item.back() == ' ') item.remove_suffix(1);
    if (item.empty()) {
      // Only "(5,)" may end in a comma: nothing after it, and something before it.
      if (comma != inside.size() || dims->empty()) return false;
      break;
    }
    int64_t v = 0;
    const auto [end, ec] = std::from_chars(item.data(), item.data() + item.size(), v);
    if (ec != std::errc() || end != item.data() + item.size() || v < 0) return false;
    dims->push_back(v);
    trailing_comma = comma != inside.size();
    start = comma + 1;
  }
  // A one-dimensional tuple needs its comma, "(5,)"; "(5)" is a number in parentheses.
  return !(dims->size() == 1 && !trailing_comma);
}

std::string NpyUnquoted(const std::string& value) {
  const bool quoted =
      value.size() >= 2 && (value.front() == '\'' || value.front() == '"') && value.back() == value.front();
  return quoted ? value.substr(1, value.size() - 2) : "";
}

NpyHeader ParseNpyHeader(std::string_view bytes, const std::string& source) {
  const NpyPreamble p = ReadNpyPreamble(bytes, source);
  if (p.header_bytes > bytes.size() - p.header_start) {
    throw NpyTruncatedHeader(source, p.header_start + p.header_bytes, bytes.size());
  }
  const std::map<std::string, std::string> fields =
      NpyHeaderFields(std::string(bytes.substr(p.header_start, p.header_bytes)), source);
  NpyHeader h;
  h.descr_as_written = fields.at("descr");
  h.descr = NpyUnquoted(h.descr_as_written);
  h.fortran_order = fields.at("fortran_order");
  h.shape_as_written = fields.at("shape");
  if (!ParseNpyShape(h.shape_as_written, &h.shape)) {
    throw InputError(source, "shape " + Quoted(h.shape_as_written) + ": expected a tuple of non-negative integers");
  }
  h.data_start = p.header_start + p.header_bytes;
  return h;
}

}  // namespace hoilcd
