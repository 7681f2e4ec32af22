// Suite files (`hoilcd suite SUITE`): the sequences of a benchmark suite, each a scene file or a
// generator spec with seeds, scene overrides and a dev/test split, read with every problem named
// by file and JSON pointer; and the sorted list of (sequence, seed) runs. Running them: suite.h.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace hoilcd {

// One sequence of a suite file.
struct SuiteSequence {
  std::string name;               // unique in the suite; letters, digits, '.', '_', '-'
  std::string scene_path;         // a scene file, resolved against the suite file's folder ("" when generated)
  bool generated = false;         // true: the scene comes from the generator
  std::string layout;             // generator layout family or "mixed"
  uint64_t generator_seed = 0;    // generator seed
  int generator_index = 0;        // generator scene index
  std::vector<int> seeds;         // scene seeds to run, each once
  std::vector<std::string> sets;  // "key=value" scene overrides, applied before the seed
  std::string split;              // "dev" or "test"
};

struct Suite {
  std::string path;  // the suite file as given
  std::string name, description;
  std::vector<SuiteSequence> sequences;
};

// Reads a suite file; InputError listing every problem as "FILE: /json/pointer: what was expected".
// Unknown keys are errors. Scene files are not opened here: a missing one fails its runs only.
Suite ReadSuite(const std::string& path);
Suite ParseSuite(const std::string& text, const std::string& path);  // the same from bytes

// One run of a suite: a sequence and a seed.
struct SuiteRunSpec {
  size_t sequence = 0;  // index into Suite::sequences
  int seed = 1;
  std::string name;  // "<sequence>-seed<S>": its folder under runs/ and its name in the report
};

// A run's name, "<sequence>-seed<S>": its folder under runs/ and its name in the report.
std::string SuiteRunName(const std::string& sequence, int64_t seed);

// The runs of the sequences in `split` ("dev", "test" or "all"), sorted by name (so a later
// --shard I/N can take every N-th).
std::vector<SuiteRunSpec> SuiteRuns(const Suite& suite, const std::string& split);

}  // namespace hoilcd
