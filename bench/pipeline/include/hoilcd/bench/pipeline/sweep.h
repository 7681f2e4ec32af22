// Parameter sweeps (`hoilcd sweep`): the cross product of listed scene values × seeds 1..N, each
// run through RunScene with its report kept. Shards split the runs for job arrays. The summary
// over seeds and the merge of shard outputs are in sweep_summary.h.
#pragma once

#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "hoilcd/bench/pipeline/run.h"
#include "hoilcd/bench/pipeline/shard.h"
#include "hoilcd/bench/runner/runner.h"
#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

// Splits on commas outside brackets, braces and JSON strings: "0,[1,2],3" -> "0", "[1,2]", "3".
// Throws InputError(where, ...) on unbalanced brackets or an empty item.
std::vector<std::string> SplitTopLevelCommas(const std::string& text, const std::string& where);

// One swept scene value: what `--set KEY=V1,V2,...` lists.
struct SweepAxis {
  std::string key;                  // scene path as ApplyOverride takes it, e.g. "crowd.walkers"
  std::vector<std::string> values;  // canonical texts (valid JSON re-dumped compactly), as listed
};

// Parses "KEY=V1,V2,..."; throws InputError("--set", ...) naming what is wrong.
SweepAxis ParseSweepAxis(const std::string& key_equals_values);

// One run of a sweep: a value for every axis and a seed.
struct SweepRunSpec {
  std::vector<std::pair<std::string, std::string>> settings;  // (key, canonical value), axis order
  int seed = 1;                                               // scene seed override

  std::string Name() const;  // "key=value,...,seed=S": the run's identity
  // Name() with characters unsafe in paths replaced by '_'; a name longer than kMaxFolderName
  // bytes (many --set keys) keeps its first bytes and ends in '~' and a hash of the whole name,
  // so that it fits a file system's 255-byte limit and stays distinct.
  static constexpr size_t kMaxFolderName = 200;
  std::string FolderName() const;
  std::vector<std::string> Overrides() const;  // for LoadScene: "key=value"..., "seed=S"
  nlohmann::json ToJson() const;
  static SweepRunSpec FromJson(const nlohmann::json& j);  // throws InputError("sweep run", ...)
};

// What a sweep runs. Shards of one sweep must have equal plans (ToJson, apart from scene_path:
// the scene hash identifies the scene) to be merged.
struct SweepPlan {
  std::string scene_path;       // scene file as given (in ToJson through SafeText: shown, never opened)
  std::string scene_name;       // its "name"
  std::string scene_hash;       // hash of the scene without the sweep's overrides
  std::vector<SweepAxis> axes;  // in --set order
  int seeds = 1;                // seeds 1..seeds
  nlohmann::json bench;         // methods and protocol settings (BenchSettingsJson)

  // Value combinations of the axes in cross-product order (first axis slowest).
  std::vector<std::vector<std::pair<std::string, std::string>>> Combinations() const;
  // Every combination x seeds 1..seeds, sorted by Name().
  std::vector<SweepRunSpec> Runs() const;
  // The runs of one shard: Runs()[k] for k % count == index (round robin over the sorted list).
  std::vector<SweepRunSpec> ShardRuns(const Shard& shard) const;
  // Parsed data (the command line or a plan file), not options: no table, its checks are by hand.
  std::string Check() const;
  nlohmann::json ToJson() const;
  static SweepPlan FromJson(const nlohmann::json& j, const std::string& where);
};

// Loads the scene, parses every --set, and loads each combination once so a bad value fails
// before anything renders. Throws InputError naming the flag or the scene path.
SweepPlan MakeSweepPlan(const std::string& scene_path, const std::vector<std::string>& sets, int seeds,
                        const BenchOptions& bench);

// Defaults and ranges: Table() in sweep.cpp.
struct SweepOptions {
  std::string output_dir;  // OUT: runs/<FolderName>/ and sweep.json (the shard marker) go here
  Shard shard;             // which part of the run list to do (default: all of it); a parsed
                           // value with its own Check(), so only a rule of the table
  RunOptions run;          // dataset cache folder, threads, cancellation

  SweepOptions();  // the registered defaults
  // Every field once: name, default, unit, range, description.
  static const OptionTable<SweepOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

// Runs the shard's runs through RunScene, each report in OUT/runs/<FolderName>/ with the run's
// sweep_run.json beside it; OUT/sweep.json records the plan and the shard, and says finished
// once every run is done. A run whose sweep_run.json already matches its scene hash and bench
// settings is kept, not rerun (a preempted job resumes). before_run, if set, is called first
// with (1-based position, run count, run, kept).
using SweepRunCallback = std::function<void(int, int, const SweepRunSpec&, bool)>;
void RunSweep(const SweepPlan& plan, const BenchOptions& bench, const SweepOptions& options,
              const SweepRunCallback& before_run = nullptr);

// "key=value,..." of settings in axis order: a combination's name.
std::string SweepSettingsName(const std::vector<std::pair<std::string, std::string>>& settings);

// `text` with characters unsafe in file names replaced by '_'.
std::string SweepSafeName(const std::string& text);

// A sweep output file as JSON; InputError(path, ...) if unreadable or not JSON.
nlohmann::json ReadSweepJson(const std::string& path);

}  // namespace hoilcd
