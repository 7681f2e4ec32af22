// Loop-closure scores of any method as a file: CSV `query,reference,score` (frame indices; pairs
// left out are unscored) or a NumPy .npy dense frames x frames float32/float64 matrix (NaN =
// unscored). Read for `hoilcd evaluate`, written by `hoilcd bench --dump-scores`. A file is
// checked against the dataset's size before its body is read, and one without a single score is
// refused: its metrics would be those of a random order.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "hoilcd/bench/evaluation/protocol.h"

namespace hoilcd {

// The largest magnitude of a score, in files and in memory: it leaves room below the lowest score
// of a query for its unscored pairs.
inline constexpr double kMaxAbsScore = 1e300;

// Scores of (query frame, reference frame) pairs of one dataset; higher = more alike.
struct ScoreMatrix {
  int frames = 0;
  std::vector<double> values;     // row-major frames x frames: [query * frames + reference], NaN = unscored
  std::string source = "scores";  // what errors about the scores name: their file

  static ScoreMatrix Unscored(int frames);  // every pair NaN
  double At(int query, int reference) const { return values[static_cast<size_t>(query) * frames + reference]; }
  double& At(int query, int reference) { return values[static_cast<size_t>(query) * frames + reference]; }
};

// CSV text with header `query,reference,score`, one pair a line of at most 128 bytes, frames in
// [0, frames), finite scores, each pair at most once, at least one pair. `source` names the file
// in errors (InputError "FILE:LINE"), which quote its bytes through SafeText.
ScoreMatrix ScoresFromCsv(std::string_view text, const std::string& source, int frames);

// The bytes of a .npy file (format version 1, 2 or 3) whose header is exactly numpy's dict of
// 'descr' (little-endian float32 or float64), 'fortran_order' (False) and 'shape'
// ((frames, frames)); elements finite or NaN, not all NaN. Errors name `source` and what was
// expected.
ScoreMatrix ScoresFromNpy(std::string_view bytes, const std::string& source, int frames);

// Reads `path` by its extension: .npy as ScoresFromNpy, anything else as CSV. Only a regular
// file (RegularFile, core/util/file_io.h); a .npy's header is read and checked, then its size
// against the header, before its body; a CSV longer than frames x frames lines is refused by
// its size and read line by line.
ScoreMatrix ReadScoresFile(const std::string& path, int frames);

// Every (query, database frame) pair of `queries` with its score (scores[i] parallel to
// queries[i].database), in query then database order, scores printed so they read back exactly.
std::string ScoresToCsv(const std::vector<Query>& queries, const std::vector<std::vector<double>>& scores);

}  // namespace hoilcd
