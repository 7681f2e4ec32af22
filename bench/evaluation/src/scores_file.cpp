#include "hoilcd/bench/evaluation/scores_file.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <sstream>

#include "hoilcd/bench/evaluation/npy.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/file_io.h"
#include "hoilcd/core/util/safe_text.h"

namespace hoilcd {
namespace {

constexpr const char* kCsvHeader = "query,reference,score";
constexpr int kMaxProblems = 10;  // a broken file of a million lines names its first few
// The longest CSV line: two frame indices and a score of 17 significant digits take ~45 bytes.
constexpr size_t kMaxCsvLineBytes = 128;
constexpr size_t kCsvReadBlockBytes = size_t{1} << 20;
constexpr size_t kQuoteBytes = 80;  // of a file's text quoted in a message

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
      return Report("score " + Quoted(fields[2]) +
                    ": beyond the range of a double; expected a finite number of "
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
  std::string line;            // the start of a line whose end is in a later block
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

// The bytes per element of a .npy header that describes this dataset's frames x frames matrix.
size_t CheckNpyHeader(const std::string& header, const std::string& source, int frames) {
  const std::map<std::string, std::string> fields = NpyHeaderFields(header, source);
  const std::string& descr = fields.at("descr");
  size_t item = 0;
  if (NpyUnquoted(descr) == "<f8") {
    item = 8;
  } else if (NpyUnquoted(descr) == "<f4") {
    item = 4;
  } else {
    throw InputError(source,
                     "dtype " + SafeText(descr) + ": expected float64 ('<f8') or float32 ('<f4')" +
                         (NpyUnquoted(descr) == "|O" ? " (an object array holds Python objects, not numbers)" : ""));
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
  if (!ParseNpyShape(shape, &dims)) {
    throw InputError(source, "shape " + Quoted(shape) + ": expected a tuple of non-negative integers, " + want +
                                 " for this dataset");
  }
  if (dims.size() != 2 || dims[0] != frames || dims[1] != frames) {
    throw InputError(source,
                     "matrix shape " + SafeText(shape) + ": expected " + want + " (the dataset's frames x frames)");
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
    throw InputError(source,
                     "every element is NaN (unscored): expected at least one score (a matrix without "
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
    throw NpyTruncatedHeader(source, p.header_start + p.header_bytes, p.header_start + header.size());
  }
  const std::string rest = header.substr(p.header_bytes);  // the body's first bytes
  header.resize(p.header_bytes);
  const size_t item = CheckNpyHeader(header, source, frames);
  const uint64_t data_start = p.header_start + p.header_bytes;
  const uint64_t data_bytes = static_cast<uint64_t>(frames) * static_cast<uint64_t>(frames) * item;
  // The size against the header before the body is read: a huge or sparse file stops here.
  if (file->size() != 0 && file->size() != data_start + data_bytes) {
    throw InputError(
        source, NpyDataBytesError(file->size() < data_start ? 0 : file->size() - data_start, data_bytes, item, frames));
  }
  // One byte more than the body tells a file that grew since fstat.
  const size_t wanted = static_cast<size_t>(data_bytes) + 1;
  std::string data = rest + file->Read(wanted > rest.size() ? wanted - rest.size() : 0);
  if (data.size() != data_bytes) {
    throw InputError(source, data.size() > data_bytes
                                 ? "grew while read: expected " + std::to_string(data_bytes) + " data bytes"
                                 : NpyDataBytesError(data.size(), data_bytes, item, frames));
  }
  return NpyScores(data, item, source, frames);
}

bool IsNpyPath(const std::string& path) { return path.size() >= 4 && path.compare(path.size() - 4, 4, ".npy") == 0; }

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
    throw NpyTruncatedHeader(source, p.header_start + p.header_bytes, bytes.size());
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
      const int n =
          std::snprintf(line, sizeof(line), "%d,%d,%.17g\n", queries[i].frame, queries[i].database[j], scores[i][j]);
      out.append(line, static_cast<size_t>(n));
    }
  }
  return out;
}

}  // namespace hoilcd
