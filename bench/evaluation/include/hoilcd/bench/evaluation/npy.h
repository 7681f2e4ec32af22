// NumPy .npy files: the preamble (magic, version, header length) and the header dict every .npy
// reader checks before it reads a body, shared by the scores reader (scores_file.h) and the real
// frames of `hoilcd realism` (bench/realism). Hand-written: Debian 12 packages no C++ .npy reader,
// and the format is a short text header followed by raw little-endian values.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "hoilcd/core/util/error.h"

namespace hoilcd {

// numpy writes a header of ~120 bytes and reads none longer than 10000 by default.
inline constexpr size_t kMaxNpyHeaderBytes = size_t{1} << 16;
inline constexpr size_t kNpyPreambleBytes = 12;  // magic, version, header length (2 or 4 bytes)

// Where a .npy file's header lies.
struct NpyPreamble {
  size_t header_start = 0;
  size_t header_bytes = 0;
};

// From a file's first kNpyPreambleBytes (or all of a shorter file); InputError(source, ...) when
// the magic, version or header length is wrong.
NpyPreamble ReadNpyPreamble(std::string_view bytes, const std::string& source);

// InputError(source, "truncated .npy header: ...") for a file of `held` bytes that needed `needed`.
InputError NpyTruncatedHeader(const std::string& source, size_t needed, size_t held);

// The fields of a .npy header, a Python dict literal such as
// {'descr': '<f8', 'fortran_order': False, 'shape': (5, 5), }, each value as written (quotes and
// brackets kept). Exactly numpy's three keys, each once; InputError(source, ...) otherwise.
std::map<std::string, std::string> NpyHeaderFields(const std::string& header, const std::string& source);

// A shape tuple as written, "(5, 5)", "(5,)" or "()": its dimensions, or false when it is not a
// tuple of non-negative decimal integers.
bool ParseNpyShape(const std::string& text, std::vector<int64_t>* dims);

// The text inside a quoted string value ('<f8' or "<f8"), or "" when `value` is no string.
std::string NpyUnquoted(const std::string& value);

// The header of a whole .npy file held in memory: dtype, order and shape, and where the body starts.
struct NpyHeader {
  std::string descr;             // dtype without quotes, e.g. "<f4"; "" when it was no string
  std::string descr_as_written;  // for messages
  std::string fortran_order;     // "True" or "False" as written
  std::vector<int64_t> shape;
  std::string shape_as_written;
  size_t data_start = 0;  // offset of the body in the file
};
// InputError(source, ...) for a bad preamble or header, or a shape that is no tuple of integers.
NpyHeader ParseNpyHeader(std::string_view bytes, const std::string& source);

}  // namespace hoilcd
