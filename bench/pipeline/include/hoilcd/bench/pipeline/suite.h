// Benchmark suites (`hoilcd suite`): a JSON file listing sequences (a scene file or a generator
// spec, each with seeds, --set overrides and a dev/test split); every (sequence, seed) runs through
// RunScene with its report kept, and the reports are summarised over runs (suite_summary.h).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "hoilcd/bench/evaluation/suite_summary.h"
#include "hoilcd/bench/pipeline/run.h"
#include "hoilcd/bench/pipeline/suite_file.h"
#include "hoilcd/bench/runner/runner.h"
#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

// Defaults and ranges: Table() in suite.cpp.
struct SuiteOptions {
  std::string output_dir;  // OUT: suite.json, scenes/, runs/<name>-seed<S>/, suite_report.{json,md}
  std::string split;       // "dev", "test" or "all"
  RunOptions run;          // dataset cache folder, threads, cancellation

  SuiteOptions();  // the registered defaults
  static const OptionTable<SuiteOptions>& Table();
  std::string Check() const;  // "" when valid, else the first problem
};

// Runs every run of the split (SuiteRuns) through RunScene, each report in OUT/runs/<name>/ with its
// suite_run.json beside it (a run whose record matches its scene hash and bench settings is kept,
// not rerun); a generated sequence's scene is written to OUT/scenes/<sequence>.json first. A run
// that throws is recorded with its message and the others go on (Ctrl-C still stops the suite).
// Writes OUT/suite_report.json and OUT/suite_report.md atomically and returns the summary;
// before_run, if set, is called with (1-based position, run count, run, kept).
using SuiteRunCallback = std::function<void(int, int, const SuiteRunSpec&, bool)>;
SuiteSummary RunSuite(const Suite& suite, const BenchOptions& bench, const SuiteOptions& options,
                      const SuiteRunCallback& before_run = nullptr);

}  // namespace hoilcd
