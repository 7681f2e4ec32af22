// Benchmark suites (`hoilcd suite`): a JSON file listing sequences (a scene file or a generator
// spec, each with seeds, --set overrides and a dev/test split); every (sequence, seed) runs through
// RunScene with its report kept, and the reports are summarised over runs (suite_summary.h).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "hoilcd/bench/evaluation/suite_summary.h"
#include "hoilcd/bench/pipeline/run.h"
#include "hoilcd/bench/runner/runner.h"
#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

// One sequence of a suite file.
struct SuiteSequence {
  std::string name;                // unique in the suite; letters, digits, '.', '_', '-'
  std::string scene_path;          // a scene file, resolved against the suite file's folder ("" when generated)
  bool generated = false;          // true: the scene comes from the generator
  std::string layout;              // generator layout family or "mixed"
  uint64_t generator_seed = 0;     // generator seed
  int generator_index = 0;         // generator scene index
  std::vector<int> seeds;          // scene seeds to run, each once
  std::vector<std::string> sets;   // "key=value" scene overrides, applied before the seed
  std::string split;               // "dev" or "test"
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
  std::string name;     // "<sequence>-seed<S>": its folder under runs/ and its name in the report
};

// The runs of the sequences in `split` ("dev", "test" or "all"), sorted by name (so a later
// --shard I/N can take every N-th).
std::vector<SuiteRunSpec> SuiteRuns(const Suite& suite, const std::string& split);

// Defaults and ranges: Table() in suite.cpp.
struct SuiteOptions {
  std::string output_dir;  // OUT: suite.json, scenes/, runs/<name>-seed<S>/, suite_report.{json,md}
  std::string split;       // "dev", "test" or "all"
  RunOptions run;          // dataset cache folder, threads, cancellation

  SuiteOptions();  // the registered defaults
  static const OptionTable<SuiteOptions>& Table();
  std::string Check() const;  // "" when valid, else the first problem
};

// Runs every run of the split through RunScene, each report in OUT/runs/<name>/ with its
// suite_run.json beside it (a run whose record matches its scene hash and bench settings is kept,
// not rerun); a generated sequence's scene is written to OUT/scenes/<sequence>.json first. A run
// that throws is recorded with its message and the others go on (Ctrl-C still stops the suite).
// Writes OUT/suite_report.json and OUT/suite_report.md atomically and returns the summary;
// before_run, if set, is called with (1-based position, run count, run, kept).
using SuiteRunCallback = std::function<void(int, int, const SuiteRunSpec&, bool)>;
SuiteSummary RunSuite(const Suite& suite, const BenchOptions& bench, const SuiteOptions& options,
                      const SuiteRunCallback& before_run = nullptr);

}  // namespace hoilcd
