#include "hoilcd/bench/evaluation/scores_file.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <sstream>

#include "hoilcd/core/util/safe_text.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/file_io.h"

namespace hoilcd {
namespace {

constexpr const char* kCsvHeader = "query,reference,score";
constexpr int kMaxProblems = 10;         // a broken file of a million lines names its first few
// The longest CSV line: two frame indices and a score of 17 significant digits take ~45 bytes.
constexpr size_t kMaxCsvLineBytes = 128;
constexpr size_t kCsvReadBlockBytes = size_t{1} << 20;
// numpy writes a header of ~120 bytes and reads none longer than 10000 by default.
constexpr size_t kMaxNpyHeaderBytes = size_t{1} << 16;
constexpr size_t kNpyPreambleBytes = 12;  // magic, version, header length (2 or 4 bytes)
constexpr size_t kQuoteBytes = 80;        // of a file's text quoted in a message

std::string Quoted(std::string_view bytes) {
  return "'" + SafeText(bytes.substr(0, kQuoteBytes)) + (bytes.size() > kQuoteBytes ? "...'" : "'");
}

bool ParseFrame(std::string_view field, int frames, int* out) {
  int64_t v = 0;
  const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
  if (ec != std::errc() || end != field.data() + field.size() || v < 0 || v >= frames) return false;
  *out = static_cast<int>(v);
  return true;
}

std::string FrameRange(int frames) { return "a frame index in 0.." + std::to_string(frames - 1); }

// A scores CSV read line by line, from a whole text or from a file block by block: the same
// checks either way, the first kMaxProblems problems named and the rest counted.
class CsvScores {
 public:
  CsvScores(std::string source, int frames) : source_(std::move(source)), matrix_(ScoreMatrix::Unscored(frames)) {
    matrix_.source = source_;
  }

  // One line without its '\n'. False once the rest cannot be read (the header is wrong).
  bool Line(std::string_view line) {
    ++line_number_;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (!header_seen_) {
      header_seen_ = true;
      if (line == kCsvHeader) return true;
      Report(std::string("expected the header '") + kCsvHeader + "', got " + Quoted(line));
      return false;  // without the header the columns are unknown
    }
    if (line.empty()) return true;
    if (line.size() > kMaxCsvLineBytes) {
      Report("line " + Quoted(line) + " is longer than " + std::to_string(kMaxCsvLineBytes) +
             " bytes: expected query,reference,score");
      return true;
    }
    Pair(line);
    return true;
  }

  // The matrix, or InputError with every problem found; a file without a pair is one.
  ScoreMatrix Finish() {
    if (!header_seen_) {
      problems_.Add(source_ + ":1", std::string("expected the header '") + kCsvHeader + "', got an empty file");
    } else if (count_ == 0 && pairs_ == 0) {
      problems_.Add(source_, std::string("holds the header and no pair: expected at least one line ") +
                                 "query,reference,score (a file without scores would rank every database in a "
                                 "random order)");
    }
    if (count_ > kMaxProblems) {
      problems_.Add(source_, std::to_string(count_ - kMaxProblems) + "+ further problems not listed");
    }
    problems_.ThrowIfAny();
    return std::move(matrix_);
  }

 private:
  void Report(const std::string& message) {
    if (count_ < kMaxProblems) problems_.Add(source_ + ":" + std::to_string(line_number_), message);
    ++count_;
  }

  void Pair(std::string_view line) {
    std::string_view fields[3];
    int n = 0;
    size_t start = 0;
    for (size_t i = 0; i <= line.size() && n <= 3; ++i) {
      if (i == line.size() || line[i] == ',') {
        if (n < 3) fields[n] = line.substr(start, i - start);
        ++n;
        start = i + 1;
      }
    }
    if (n != 3) return Report("expected 3 fields (query,reference,score), got " + std::to_string(n));
    const int frames = matrix_.frames;
    int query = 0, reference = 0;
    if (!ParseFrame(fields[0], frames, &query)) {
      return Report("query " + Quoted(fields[0]) + ": expected " + FrameRange(frames));
    }
    if (!ParseFrame(fields[1], frames, &reference)) {
      return Report("reference " + Quoted(fields[1]) + ": expected " + FrameRange(frames));
    }
    double score = 0;
    const auto [score_end, ec] = std::from_chars(fields[2].data(), fields[2].data() + fields[2].size(), score);
    if (ec == std::errc::result_out_of_range) {
      return Report("score " + Quoted(fields[2]) + ": beyond the range of a double; expected a finite number of "
                    "magnitude at most 1e300");
    }
    if (ec != std::errc() || score_end != fields[2].data() + fields[2].size()) {
      return Report("score " + Quoted(fields[2]) + ": expected a number");
    }
    if (std::isnan(score)) return Report("score is NaN: leave the pair out to mark it unscored");
    if (!(std::fabs(score) <= kMaxAbsScore)) {
      return Report("score " + Quoted(fields[2]) + ": expected a finite number of magnitude at most 1e300");
    }
    double& cell = matrix_.At(query, reference);
    if (!std::isnan(cell)) {
      return Report("duplicate pair query " + std::to_string(query) + ", reference " + std::to_string(reference) +
                    ": each pair at most once");
    }
    cell = score;
    ++pairs_;
  }

  std::string source_;
  ScoreMatrix matrix_;
  ProblemCollector problems_;
  int count_ = 0;
  int line_number_ = 0;
  int64_t pairs_ = 0;
  bool header_seen_ = false;
};

// The largest scores CSV of a dataset of `frames` frames: its header and every pair once.
uint64_t MaxCsvBytes(int frames) {
  return std::char_traits<char>::length(kCsvHeader) + 2 +
         static_cast<uint64_t>(frames) * static_cast<uint64_t>(frames) * (kMaxCsvLineBytes + 2);
}

ScoreMatrix ReadCsvFile(RegularFile* file, int frames) {
  const uint64_t max_bytes = MaxCsvBytes(frames);
  const auto too_long = [&](const std::string& size) {
    return InputError(file->path(), "is " + size + " bytes: a scores CSV of this dataset's " + std::to_string(frames) +
                                        " frames holds at most " + std::to_string(frames) + " x " +
                                        std::to_string(frames) + " lines of at most " +
                                        std::to_string(kMaxCsvLineBytes) + " bytes (" + std::to_string(max_bytes) +
                                        " bytes)");
  };
  if (file->size() > max_bytes) throw too_long(std::to_string(file->size()));
  CsvScores csv(file->path(), frames);
  std::string line;       // the start of a line whose end is in a later block
  bool too_long_line = false;  // the rest of a line already reported as too long is skipped
  uint64_t read = 0;
  for (std::string block; !(block = file->Read(kCsvReadBlockBytes)).empty();) {
    read += block.size();
    if (read > max_bytes) throw too_long("more than " + std::to_string(max_bytes));  // grew, or stat did not know
    for (size_t pos = 0; pos < block.size();) {
      const size_t end = std::min(block.find('\n', pos), block.size());
      if (!too_long_line) line.append(block, pos, end - pos);
      if (end == block.size()) {  // the line goes on in the next block
        if (!too_long_line && line.size() > kMaxCsvLineBytes) {
          if (!csv.Line(line)) return csv.Finish();
          too_long_line = true;
          line.clear();
        }
        break;
      }
      if (!too_long_line && !csv.Line(line)) return csv.Finish();
      too_long_line = false;
      line.clear();
      pos = end + 1;
    }
  }
  if (!too_long_line && !line.empty()) csv.Line(line);
  return csv.Finish();
}

// Where a .npy file's header lies, from its first kNpyPreambleBytes (or all of a shorter file).
struct NpyPreamble {
  size_t header_start = 0;
  size_t header_bytes = 0;
};

InputError TruncatedHeader(const std::string& source, size_t needed, size_t held) {
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
    if (bytes.size() < kNpyPreambleBytes) throw TruncatedHeader(source, kNpyPreambleBytes, bytes.size());
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

// The fields of a .npy header, a Python dict literal such as
// {'descr': '<f8', 'fortran_order': False, 'shape': (5, 5), }, each value as written (quotes and
// brackets kept). Exactly numpy's three keys, each once.
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
  if (i == header.size() || header[i] != '{') fail("expected a Python dict {'descr': ..., 'fortran_order': ..., 'shape': ...}");
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

// A shape tuple as written, "(5, 5)", "(5,)" or "()": its dimensions, or false when it is not a
// tuple of non-negative decimal integers.
bool ParseShape(const std::string& text, std::vector<int64_t>* dims) {
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

// The text inside a quoted string value ('<f8' or "<f8"), or "" when `value` is no string.
std::string Unquoted(const std::string& value) {
  const bool quoted = value.size() >= 2 && (value.front() == '\'' || value.front() == '"') && value.back() == value.front();
  return quoted ? value.substr(1, value.size() - 2) : "";
}

// The bytes per element of a .npy header that describes this dataset's frames x frames matrix.
size_t CheckNpyHeader(const std::string& header, const std::string& source, int frames) {
  const std::map<std::string, std::string> fields = NpyHeaderFields(header, source);
  const std::string& descr = fields.at("descr");
  size_t item = 0;
  if (Unquoted(descr) == "<f8") {
    item = 8;
  } else if (Unquoted(descr) == "<f4") {
    item = 4;
  } else {
    throw InputError(source, "dtype " + SafeText(descr) + ": expected float64 ('<f8') or float32 ('<f4')" +
                                 (Unquoted(descr) == "|O" ? " (an object array holds Python objects, not numbers)" : ""));
  }
  const std::string& fortran_order = fields.at("fortran_order");
  if (fortran_order == "True") {
    throw InputError(source, "fortran_order True: expected a C-order matrix (numpy.ascontiguousarray)");
  }
  if (fortran_order != "False") {
    throw InputError(source, "fortran_order " + Quoted(fortran_order) + ": expected False (a C-order matrix)");
  }
  const std::string& shape = fields.at("shape");
  const std::string want = "(" + std::to_string(frames) + ", " + std::to_string(frames) + ")";
  std::vector<int64_t> dims;
  if (!ParseShape(shape, &dims)) {
    throw InputError(source, "shape " + Quoted(shape) + ": expected a tuple of non-negative integers, " + want +
                                 " for this dataset");
  }
  if (dims.size() != 2 || dims[0] != frames || dims[1] != frames) {
    throw InputError(source, "matrix shape " + SafeText(shape) + ": expected " + want +
                                 " (the dataset's frames x frames)");
  }
  return item;
}

std::string NpyDataBytesError(uint64_t data_bytes, uint64_t expected, size_t item, int frames) {
  return "holds " + std::to_string(data_bytes) + " data bytes: expected " + std::to_string(expected) + " for a (" +
         std::to_string(frames) + ", " + std::to_string(frames) + ") matrix of " + std::to_string(item * 8) +
         "-bit floats";
}

// The elements of a .npy body of exactly frames x frames `item`-byte floats.
ScoreMatrix NpyScores(std::string_view data, size_t item, const std::string& source, int frames) {
  static_assert(std::numeric_limits<double>::is_iec559, "IEEE 754 floats");
  ScoreMatrix m = ScoreMatrix::Unscored(frames);
  m.source = source;
  bool any = false;
  for (size_t c = 0; c < m.values.size(); ++c) {
    double v = 0;
    if (item == 8) {
      std::memcpy(&v, data.data() + c * 8, 8);  // little-endian host (x86-64, arm64)
    } else {
      float f = 0;
      std::memcpy(&f, data.data() + c * 4, 4);
      v = f;
    }
    if (std::isnan(v)) continue;
    if (!(std::fabs(v) <= kMaxAbsScore)) {
      std::ostringstream what;
      what << "element [" << c / static_cast<size_t>(frames) << ", " << c % static_cast<size_t>(frames) << "] = " << v
           << ": expected a finite score of magnitude at most 1e300, or NaN for unscored";
      throw InputError(source, what.str());
    }
    m.values[c] = v;
    any = true;
  }
  if (!any) {
    throw InputError(source, "every element is NaN (unscored): expected at least one score (a matrix without "
                             "scores would rank every database in a random order)");
  }
  return m;
}

ScoreMatrix ReadNpyFile(RegularFile* file, int frames) {
  const std::string& source = file->path();
  const std::string preamble = file->Read(kNpyPreambleBytes);
  const NpyPreamble p = ReadNpyPreamble(preamble, source);
  // What the preamble read past the header's start belongs to the header (version 1: 2 bytes).
  std::string header = preamble.substr(std::min(preamble.size(), p.header_start));
  if (header.size() < p.header_bytes) header += file->Read(p.header_bytes - header.size());
  if (header.size() < p.header_bytes) {
    throw TruncatedHeader(source, p.header_start + p.header_bytes, p.header_start + header.size());
  }
  const std::string rest = header.substr(p.header_bytes);  // the body's first bytes
  header.resize(p.header_bytes);
  const size_t item = CheckNpyHeader(header, source, frames);
  const uint64_t data_start = p.header_start + p.header_bytes;
  const uint64_t data_bytes = static_cast<uint64_t>(frames) * static_cast<uint64_t>(frames) * item;
  // The size against the header before the body is read: a huge or sparse file stops here.
  if (file->size() != 0 && file->size() != data_start + data_bytes) {
    throw InputError(source, NpyDataBytesError(file->size() < data_start ? 0 : file->size() - data_start,
                                               data_bytes, item, frames));
  }
  // One byte more than the body tells a file that grew since fstat.
  const size_t wanted = static_cast<size_t>(data_bytes) + 1;
  std::string data = rest + file->Read(wanted > rest.size() ? wanted - rest.size() : 0);
  if (data.size() != data_bytes) {
    throw InputError(source, data.size() > data_bytes ? "grew while read: expected " + std::to_string(data_bytes) +
                                                            " data bytes"
                                                      : NpyDataBytesError(data.size(), data_bytes, item, frames));
  }
  return NpyScores(data, item, source, frames);
}

bool IsNpyPath(const std::string& path) {
  return path.size() >= 4 && path.compare(path.size() - 4, 4, ".npy") == 0;
}

}  // namespace

ScoreMatrix ScoreMatrix::Unscored(int frames) {
  HOILCD_CHECK(frames >= 0);
  ScoreMatrix m;
  m.frames = frames;
  m.values.assign(static_cast<size_t>(frames) * frames, std::numeric_limits<double>::quiet_NaN());
  return m;
}

ScoreMatrix ScoresFromCsv(std::string_view text, const std::string& source, int frames) {
  CsvScores csv(source, frames);
  for (size_t pos = 0; pos < text.size();) {
    const size_t end = std::min(text.find('\n', pos), text.size());
    if (!csv.Line(text.substr(pos, end - pos))) break;
    pos = end + 1;
  }
  return csv.Finish();
}

// Hand-written: Debian 12 packages no C++ .npy reader, and the format is a short text header
// followed by raw little-endian values.
ScoreMatrix ScoresFromNpy(std::string_view bytes, const std::string& source, int frames) {
  const NpyPreamble p = ReadNpyPreamble(bytes, source);
  if (p.header_bytes > bytes.size() - p.header_start) {
    throw TruncatedHeader(source, p.header_start + p.header_bytes, bytes.size());
  }
  const size_t item = CheckNpyHeader(std::string(bytes.substr(p.header_start, p.header_bytes)), source, frames);
  const std::string_view data = bytes.substr(p.header_start + p.header_bytes);
  const uint64_t data_bytes = static_cast<uint64_t>(frames) * static_cast<uint64_t>(frames) * item;
  if (data.size() != data_bytes) throw InputError(source, NpyDataBytesError(data.size(), data_bytes, item, frames));
  return NpyScores(data, item, source, frames);
}

ScoreMatrix ReadScoresFile(const std::string& path, int frames) {
  RegularFile file(path);
  return IsNpyPath(path) ? ReadNpyFile(&file, frames) : ReadCsvFile(&file, frames);
}

std::string ScoresToCsv(const std::vector<Query>& queries, const std::vector<std::vector<double>>& scores) {
  HOILCD_CHECK(queries.size() == scores.size());
  std::string out = std::string(kCsvHeader) + "\n";
  char line[96];
  for (size_t i = 0; i < queries.size(); ++i) {
    HOILCD_CHECK(queries[i].database.size() == scores[i].size());
    for (size_t j = 0; j < scores[i].size(); ++j) {
      // %.17g prints every double so that it parses back to the same bits.
      const int n = std::snprintf(line, sizeof(line), "%d,%d,%.17g\n", queries[i].frame, queries[i].database[j], scores[i][j]);
      out.append(line, static_cast<size_t>(n));
    }
  }
  return out;
}

}  // namespace hoilcd
