// Benchmark suites (`hoilcd suite`): a JSON file listing sequences (a scene file or a generator
// spec, each with seeds, --set overrides and a dev/test split); every (sequence, seed) of a split,
// or of one shard of it, runs through RunScene with its report kept. The report over runs, and the
// merge of shards into it: suite_report.h.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hoilcd/bench/evaluation/suite_summary.h"
#include "hoilcd/bench/pipeline/run.h"
#include "hoilcd/bench/pipeline/shard.h"
#include "hoilcd/bench/pipeline/suite_file.h"
#include "hoilcd/bench/runner/runner.h"
#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

// Defaults and ranges: Table() in suite.cpp.
struct SuiteOptions {
  std::string output_dir;  // OUT: suite.json, scenes/, runs/<name>-seed<S>/
  std::string split;       // "dev", "test" or "all"
  Shard shard;             // which part of the split's sorted run list to do (default: all of it); a
                           // parsed value with its own Check(), so only a rule of the table
  RunOptions run;          // dataset cache folder, threads, cancellation

  SuiteOptions();  // the registered defaults
  static const OptionTable<SuiteOptions>& Table();
  std::string Check() const;  // "" when valid, else the first problem
};

// What makes two outputs runs of one suite, so a merge may combine them: the suite's name and
// description, the split's sequences (a scene file by the checksum of its bytes, null when it
// cannot be read, so the same suite checked out at another path is the same; a generated one by
// its spec and the generator's version) with their seeds and overrides, the split, the bench settings
// (BenchSettingsJson) and the split's run names in order.
nlohmann::json SuiteIdentity(const Suite& suite, const std::string& split, const nlohmann::json& bench);

// Runs the shard's runs of the split (every run when unsharded) through RunScene, each report in
// OUT/runs/<name>/ with its suite_run.json beside it (a run whose record matches its scene hash and
// bench settings is kept, not rerun); a generated sequence's scene is written to
// OUT/scenes/<sequence>.json first. A run that throws is recorded with its message and the others
// go on (Ctrl-C still stops the suite). OUT/suite.json records the suite, its identity and hash,
// the shard, its runs, the failed ones with their errors and whether the shard finished. Returns
// the shard's results in run order; MergeSuite (suite_report.h) makes the report from OUT.
// before_run, if set, is called with (1-based position, shard's run count, run, kept).
using SuiteRunCallback = std::function<void(int, int, const SuiteRunSpec&, bool)>;
std::vector<SuiteRunResult> RunSuite(const Suite& suite, const BenchOptions& bench, const SuiteOptions& options,
                                     const SuiteRunCallback& before_run = nullptr);

}  // namespace hoilcd
