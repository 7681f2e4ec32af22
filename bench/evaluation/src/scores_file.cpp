#include "hoilcd/bench/evaluation/scores_file.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/util/error.h"

namespace hoilcd {
namespace {

constexpr const char* kCsvHeader = "query,reference,score";
constexpr int kMaxProblems = 10;         // a broken file of a million lines names its first few
constexpr double kMaxAbsScore = 1e300;   // leaves room below the lowest score for "unscored"

// Adds the first kMaxProblems problems and counts the rest.
void Report(ProblemCollector* problems, int* count, const std::string& where, const std::string& message) {
  if (*count < kMaxProblems) problems->Add(where, message);
  ++*count;
}

bool ParseFrame(std::string_view field, int frames, int* out) {
  int64_t v = 0;
  const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
  if (ec != std::errc() || end != field.data() + field.size() || v < 0 || v >= frames) return false;
  *out = static_cast<int>(v);
  return true;
}

std::string FrameRange(int frames) { return "a frame index in 0.." + std::to_string(frames - 1); }

}  // namespace

ScoreMatrix ScoreMatrix::Unscored(int frames) {
  HOILCD_CHECK(frames >= 0);
  ScoreMatrix m;
  m.frames = frames;
  m.values.assign(static_cast<size_t>(frames) * frames, std::numeric_limits<double>::quiet_NaN());
  return m;
}

ScoreMatrix ScoresFromCsv(std::string_view text, const std::string& source, int frames) {
  ScoreMatrix m = ScoreMatrix::Unscored(frames);
  ProblemCollector problems;
  int count = 0;
  size_t pos = 0;
  int line_number = 0;
  bool header_seen = false;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    const std::string where = source + ":" + std::to_string(line_number);
    if (!header_seen) {
      header_seen = true;
      if (line != kCsvHeader) {
        Report(&problems, &count, where, std::string("expected the header '") + kCsvHeader + "', got '" +
                                             std::string(line.substr(0, 80)) + "'");
        break;  // without the header the columns are unknown
      }
      continue;
    }
    if (line.empty()) continue;
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
    if (n != 3) {
      Report(&problems, &count, where, "expected 3 fields (query,reference,score), got " + std::to_string(n));
      continue;
    }
    int query = 0, reference = 0;
    if (!ParseFrame(fields[0], frames, &query)) {
      Report(&problems, &count, where, "query '" + std::string(fields[0]) + "': expected " + FrameRange(frames));
      continue;
    }
    if (!ParseFrame(fields[1], frames, &reference)) {
      Report(&problems, &count, where, "reference '" + std::string(fields[1]) + "': expected " + FrameRange(frames));
      continue;
    }
    double score = 0;
    const auto [score_end, ec] = std::from_chars(fields[2].data(), fields[2].data() + fields[2].size(), score);
    if (ec != std::errc() || score_end != fields[2].data() + fields[2].size()) {
      Report(&problems, &count, where, "score '" + std::string(fields[2]) + "': expected a number");
      continue;
    }
    if (std::isnan(score)) {
      Report(&problems, &count, where, "score is NaN: leave the pair out to mark it unscored");
      continue;
    }
    if (!(std::fabs(score) <= kMaxAbsScore)) {
      Report(&problems, &count, where, "score '" + std::string(fields[2]) + "': expected a finite number of magnitude at most 1e300");
      continue;
    }
    double& cell = m.At(query, reference);
    if (!std::isnan(cell)) {
      Report(&problems, &count, where, "duplicate pair query " + std::to_string(query) + ", reference " +
                                                std::to_string(reference) + ": each pair at most once");
      continue;
    }
    cell = score;
  }
  if (!header_seen) problems.Add(source + ":1", std::string("expected the header '") + kCsvHeader + "', got an empty file");
  if (count > kMaxProblems) problems.Add(source, std::to_string(count - kMaxProblems) + "+ further problems not listed");
  problems.ThrowIfAny();
  return m;
}

// Hand-written: Debian 12 packages no C++ .npy reader, and the format is a short text header
// followed by raw little-endian values.
ScoreMatrix ScoresFromNpy(std::string_view bytes, const std::string& source, int frames) {
  auto fail = [&](const std::string& what) { throw InputError(source, what); };
  if (bytes.size() < 10 || bytes.substr(0, 6) != std::string_view("\x93NUMPY", 6)) {
    fail("expected a NumPy .npy file (magic \\x93NUMPY)");
  }
  const auto major = static_cast<unsigned char>(bytes[6]);
  size_t header_len = 0, header_start = 0;
  if (major == 1) {
    header_len = static_cast<unsigned char>(bytes[8]) | static_cast<size_t>(static_cast<unsigned char>(bytes[9])) << 8;
    header_start = 10;
  } else if (major == 2 || major == 3) {
    if (bytes.size() < 12) fail("truncated .npy header");
    for (int i = 3; i >= 0; --i) header_len = header_len << 8 | static_cast<unsigned char>(bytes[8 + i]);
    header_start = 12;
  } else {
    fail(".npy format version " + std::to_string(major) + ": expected 1, 2 or 3");
  }
  if (header_len > bytes.size() - header_start) fail("truncated .npy header");
  const std::string header(bytes.substr(header_start, header_len));
  // The header is a Python dict literal, e.g. {'descr': '<f8', 'fortran_order': False, 'shape': (5, 5), }
  auto value_of = [&](const std::string& key) -> std::string {
    const size_t k = header.find("'" + key + "'");
    if (k == std::string::npos) fail(".npy header has no '" + key + "'");
    const size_t colon = header.find(':', k);
    if (colon == std::string::npos) fail(".npy header: no value for '" + key + "'");
    size_t v = header.find_first_not_of(' ', colon + 1);
    if (v == std::string::npos) fail(".npy header: no value for '" + key + "'");
    const char open = header[v];
    const char close = open == '\'' ? '\'' : open == '(' ? ')' : ',';
    const size_t e = header.find_first_of(std::string(1, close) + "}", v + 1);
    if (e == std::string::npos) fail(".npy header: unterminated value of '" + key + "'");
    return header.substr(v, e - v + (open == '\'' || open == '(' ? 1 : 0));
  };
  const std::string descr = value_of("descr");
  size_t item = 0;
  if (descr == "'<f8'") {
    item = 8;
  } else if (descr == "'<f4'") {
    item = 4;
  } else {
    fail("dtype " + descr + ": expected float64 ('<f8') or float32 ('<f4')");
  }
  if (value_of("fortran_order") != "False") fail("fortran_order True: expected a C-order matrix (numpy.ascontiguousarray)");
  const std::string shape = value_of("shape");
  std::vector<int64_t> dims;
  for (size_t i = 1; i < shape.size();) {
    const size_t d = shape.find_first_of("0123456789", i);
    if (d == std::string::npos) break;
    int64_t v = 0;
    const auto [end, ec] = std::from_chars(shape.data() + d, shape.data() + shape.size(), v);
    if (ec != std::errc()) fail("shape " + shape + ": expected (frames, frames)");
    dims.push_back(v);
    i = static_cast<size_t>(end - shape.data());
  }
  const std::string want = "(" + std::to_string(frames) + ", " + std::to_string(frames) + ")";
  if (dims.size() != 2 || dims[0] != frames || dims[1] != frames) {
    fail("matrix shape " + shape + ": expected " + want + " (the dataset's frames x frames)");
  }
  const size_t data_start = header_start + header_len;
  const size_t cells = static_cast<size_t>(frames) * static_cast<size_t>(frames);
  if (bytes.size() - data_start != cells * item) {
    fail("holds " + std::to_string(bytes.size() - data_start) + " data bytes: expected " + std::to_string(cells * item) +
         " for a " + want + " matrix of " + std::to_string(item * 8) + "-bit floats");
  }
  static_assert(std::numeric_limits<double>::is_iec559, "IEEE 754 floats");
  ScoreMatrix m = ScoreMatrix::Unscored(frames);
  const char* data = bytes.data() + data_start;
  for (size_t c = 0; c < cells; ++c) {
    double v = 0;
    if (item == 8) {
      std::memcpy(&v, data + c * 8, 8);  // little-endian host (x86-64, arm64)
    } else {
      float f = 0;
      std::memcpy(&f, data + c * 4, 4);
      v = f;
    }
    if (!std::isnan(v) && !(std::fabs(v) <= kMaxAbsScore)) {
      std::ostringstream what;
      what << "element [" << c / frames << ", " << c % frames << "] = " << v
           << ": expected a finite score of magnitude at most 1e300, or NaN for unscored";
      fail(what.str());
    }
    m.values[c] = v;
  }
  return m;
}

ScoreMatrix ReadScoresFile(const std::string& path, int frames) {
  const std::string bytes = ReadFileBytes(path);
  const bool npy = path.size() >= 4 && path.compare(path.size() - 4, 4, ".npy") == 0;
  return npy ? ScoresFromNpy(bytes, path, frames) : ScoresFromCsv(bytes, path, frames);
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
