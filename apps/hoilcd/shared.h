// What several subcommands share, each declared once: the --threads flag, the scene flags, the
// protocol and bench flags, the CI gate, Ctrl-C handling and the printed result table.
#pragma once

#include <atomic>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "hoilcd/bench/methods/bench_options.h"
#include "hoilcd/bench/pipeline/run.h"
#include "hoilcd/bench/runner/runner.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/option_table.h"
#include "hoilcd/sim/scene/scene.h"

namespace hoilcd {

// The check of every number flag: a finite number in `range`, else "--flag: expected a number at
// least 0, got nan" (NaN and infinities are refused; CLI11's own ranges let NaN through and print
// the bounds of a double in full).
CLI::Validator NumberIn(const OptionRange& range);

// Whether `flag` (one of the names of an option of `cmd`, e.g. "--strata") was on the command line.
bool Given(const CLI::App& cmd, const std::string& flag);
// InputError "`flag`: `why`" when `flag` was given: a flag that the mode it was given in does not
// use is refused by name before any work, never accepted and ignored.
void RefuseIfGiven(const CLI::App& cmd, const std::string& flag, const std::string& why);

// --threads N (0: the CPUs this process may use) on `cmd`, into `threads`.
void AddThreadsFlag(CLI::App* cmd, int* threads);
// --shard I/N of render, suite and sweep, into `shard`: set whenever the flag is given, even as
// --shard '' (which ParseShard then refuses), unset without it.
void AddShardFlag(CLI::App* cmd, std::optional<std::string>* shard, const std::string& description);
// --cache and --drop-datasets of the commands that render many runs (sweep, suite).
void AddManyRunsCacheFlags(CLI::App* cmd, RunOptions* run);

// SCENE, --set KEY=VALUE and --seed.
struct SceneArgs {
  std::string path;
  std::vector<std::string> overrides;
  int64_t seed = -1;
};
void AddSceneFlags(CLI::App* cmd, SceneArgs* args, bool scene_required);
Scene LoadSceneArgs(const SceneArgs& args);

// The evaluation protocol's flags (bench, run, sweep, evaluate): --protocol and --radius (alone
// in inspect, which labels under both ground truths itself) and the rest.
// `flag` for the registered field `name` of an options table (`fields`: its List()): its
// description, unit and range (or choices) come from the table, so they are written once; the help
// shows the value *member holds.
template <typename T>
CLI::Option* AddTableFlag(CLI::App* cmd, const std::string& flag, const std::vector<OptionInfo>& fields,
                          const std::string& name, T* member) {
  for (const OptionInfo& info : fields) {
    if (info.name != name) continue;
    CLI::Option* option =
        cmd->add_option(flag, *member, info.description + (info.unit.empty() ? "" : ", " + info.unit));
    if constexpr (std::is_same_v<T, std::string>) {
      if (!info.choices.empty()) option->check(CLI::IsMember(info.choices));
    } else {
      option->check(NumberIn(info.range));
    }
    return option->capture_default_str();
  }
  HOILCD_CHECK_MSG(false, "no option " + name + " in the table of " + flag);
  return nullptr;
}

void AddProtocolAndRadiusFlags(CLI::App* cmd, ProtocolOptions* protocol);
void AddProtocolFlags(CLI::App* cmd, ProtocolOptions* protocol);
// Refuses the --overlap-* flags of AddProtocolFlags when the ground truth is not overlap.
void CheckProtocolFlagsApply(const CLI::App& cmd, const ProtocolOptions& protocol);

// The methods and their options (bench, run, sweep).
struct BenchArgs {
  std::string methods;
  BenchOptions options;
  const CLI::App* cmd = nullptr;   // the command AddBenchFlags added to: which of its flags were given
  std::vector<std::string> flags;  // the flags AddBenchFlags added, protocol flags included
};
void AddBenchFlags(CLI::App* cmd, BenchArgs* args);
// The options asked for, checked; InputError naming what is wrong, or naming a flag given that
// would change nothing: --slam-backend and --loop-threshold with SLAM off, an --overlap-* flag
// without --ground-truth overlap, --detector when no method run uses keypoints.
BenchOptions ResolveBench(const BenchArgs& args, int threads);
// RefuseIfGiven on each of AddBenchFlags's flags, for a mode that runs no bench.
void RefuseBenchFlags(const BenchArgs& args, const std::string& why);

// The CI gate (bench, run, evaluate).
struct GateArgs {
  std::string baseline;
  std::string max_drop = "0";  // DropAllowance::Parse: a number in [0, 1] or "ci"
  std::string junit;
};
void AddGateFlags(CLI::App* cmd, GateArgs* args);
// The --baseline report (null without one), read before the work so a bad one fails first; one
// of another bench mode (`mode`: "online" or "offline", report.json's "mode", offline when absent)
// is refused, since its figures measure something else.
nlohmann::json ReadBaseline(const GateArgs& args, const std::string& mode = "offline");
// Compares `report` with `baseline` (ReadBaseline's) and writes JUnit XML, as asked; the exit
// code (0, or 3 on any regression).
int ApplyGate(const GateArgs& args, const nlohmann::json& baseline, const nlohmann::json& report);

// The first Ctrl-C sets the returned flag (long commands stop cleanly and can resume); a second
// ends the process at once.
std::atomic<bool>* CancelOnInterrupt();

// Each warning on stderr, one line each ("warning: ...").
void PrintWarnings(const std::vector<std::string>& warnings);

// The result table, the paper's finding and where the report is.
void PrintOutcome(const BenchResult& result, const std::string& report_dir);

}  // namespace hoilcd
