// Issue 45, the class "flags accepted and then ignored in one mode": every flag of every command is
// given to it in each of the command's modes (bench and bench --online, sweep and suite with and
// without --merge, ...) on a tiny dataset, and must either change what the command does (a probe
// of what it wrote, printed or exited with differs from the same run without the flag) or be
// refused by an error naming it. The flags come from the CLI11 app itself: a new flag without a
// row in every mode of its command fails EveryFlagOfEveryModeHasARow.
#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include <CLI/CLI.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/syscall.h>
#include <unistd.h>

#include "cli.h"
#include "hoilcd/core/util/file_io.h"
#include "run_cli.h"
#include "test_dir.h"
#include "tiny_room.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;
using Args = std::vector<std::string>;

// The files every mode's command line may name, each made (once) by the mode's set-up.
enum Fixture { kDataset, kScores, kBaselines, kShards, kSweepOutput, kSuiteFiles, kSuiteOutput };

// One run of the command line, with the path its {out} stood for.
struct CommandRun {
  test::CliOutcome outcome;
  std::string out;
};

// A text read from a run (a file, a JSON value, its output, its exit code): what must differ
// between the runs with and without a flag that acts.
using Probe = std::function<std::string(const CommandRun&)>;

enum class Expect {
  kActs,      // the probe differs from the run without the flag
  kRefused,   // a non-zero exit and an error naming the flag
  kRequired,  // the command refuses to run without it
  kThreads,   // --threads: more threads do work with --threads 3 than with --threads 1
};

struct Row {
  std::string flag;  // as CLI11 names the option (Option::get_name(): its first long name)
  Args args;         // the flag and its value; empty: the flag is in the mode's command line, the run
                     // without it leaves it out
  Expect expect;
  Probe probe = nullptr;  // kActs
  Args context = {};      // given to both runs: what the flag needs in order to apply
};

struct Mode {
  std::string name;     // "bench --online"
  std::string command;  // the subcommand whose flags the rows cover ("": hoilcd's own flags)
  Args base;            // the command line, with placeholders: {out} (a new folder per run), {dataset}, ...
  std::set<Fixture> fixtures;
  std::vector<Row> rows;
};

// The bench flags the merge modes' shards ran with: every bench flag applies to them.
const Args kRichBench = {"--methods", "slcd", "--ground-truth", "overlap", "--slam", "--loop-threshold", "5"};

std::string Source(const std::string& path) { return std::string(HOILCD_TEST_SOURCE_DIR) + "/" + path; }

std::string TextOf(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return "<no file " + path + ">";
  return ReadFileBytes(path);
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

// Probes; `path` may hold {out}.
Probe Exit() {
  return [](const CommandRun& r) { return std::to_string(r.outcome.exit_code); };
}
Probe Out() {
  return [](const CommandRun& r) { return Replace(r.outcome.out, r.out, "{out}"); };
}
Probe Err() {
  return [](const CommandRun& r) { return Replace(r.outcome.err, r.out, "{out}"); };
}
// The lines of its output that start with `prefix`, and its exit code.
Probe OutLines(const std::string& prefix) {
  return [prefix](const CommandRun& r) {
    std::string lines = "exit " + std::to_string(r.outcome.exit_code) + "\n";
    size_t start = 0;
    for (size_t end; (end = r.outcome.out.find('\n', start)) != std::string::npos; start = end + 1) {
      if (r.outcome.out.compare(start, prefix.size(), prefix) == 0)
        lines += r.outcome.out.substr(start, end - start + 1);
    }
    return lines;
  };
}
Probe Exists(const std::string& path) {
  return [path](const CommandRun& r) { return fs::exists(Replace(path, "{out}", r.out)) ? "exists" : "absent"; };
}
// The JSON values at `pointers` of the file (timings vary from run to run: name what to compare).
Probe Json(const std::string& path, const std::vector<std::string>& pointers) {
  return [path, pointers](const CommandRun& r) {
    const std::string text = TextOf(Replace(path, "{out}", r.out));
    if (text.rfind("<no file", 0) == 0)
      return text + " (exit " + std::to_string(r.outcome.exit_code) + ": " + r.outcome.err + ")";
    const nlohmann::json j = nlohmann::json::parse(text);
    std::string values;
    for (const std::string& p : pointers) {
      const nlohmann::json::json_pointer pointer(p);
      values += p + "=" + (j.contains(pointer) ? j.at(pointer).dump() : "<absent>") + "\n";
    }
    return values;
  };
}
// A folder's file names and bytes.
Probe Files(const std::string& dir) {
  return [dir](const CommandRun& r) {
    const std::string d = Replace(dir, "{out}", r.out);
    std::map<std::string, std::string> files;
    std::error_code ec;
    if (fs::is_directory(d, ec)) {
      for (const auto& e : fs::recursive_directory_iterator(d)) {
        if (e.is_regular_file()) files[fs::relative(e.path(), d).string()] = ReadFileBytes(e.path().string());
      }
    }
    std::string text;
    for (const auto& [name, bytes] : files) text += name + ":" + std::to_string(std::hash<std::string>()(bytes)) + "\n";
    return text;
  };
}

// A bench report's headline figures of `method` (not its timing).
Probe Metrics(const std::string& report, const std::string& method) {
  std::vector<std::string> pointers;
  for (const char* key : {"mrr", "recall_at_1", "recall_at_5", "pr_auc", "queries_scored", "queries_skipped"}) {
    pointers.push_back("/methods/" + method + "/" + key);
  }
  return Json(report, pointers);
}

// CPU time of each thread of this process, ns, by thread id.
std::map<std::string, uint64_t> CpuNsByThread() {
  std::map<std::string, uint64_t> ns;
  for (const auto& e : fs::directory_iterator("/proc/self/task")) {
    std::ifstream in(e.path() / "schedstat");
    uint64_t on_cpu = 0;
    if (in >> on_cpu) ns[e.path().filename().string()] = on_cpu;
  }
  return ns;
}

// Threads other than the caller that ran at least 2 ms of CPU during `fn`.
int HelpersThatWorked(const std::function<void()>& fn) {
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // earlier work's spinning ends
  const std::map<std::string, uint64_t> before = CpuNsByThread();
  fn();
  const std::map<std::string, uint64_t> after = CpuNsByThread();
  const std::string self = std::to_string(syscall(SYS_gettid));
  int helpers = 0;
  for (const auto& [tid, ns] : after) {
    const auto it = before.find(tid);
    if (tid != self && ns - (it == before.end() ? 0 : it->second) > 2'000'000) ++helpers;
  }
  return helpers;
}

// Runs `hoilcd ARGS...` (no -q added: each mode says it).
test::CliOutcome Invoke(Args args) {
  args.insert(args.begin(), "hoilcd");
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  const int code = RunCommandLine(static_cast<int>(argv.size()), argv.data());
  const std::string out = testing::internal::GetCapturedStdout();
  return {code, out, testing::internal::GetCapturedStderr()};
}

// The app's options, by any of their names: what a row's flag is, and whether it takes a value.
class Flags {
 public:
  Flags() { commands_ = AddCommands(&app_, &quiet_); }
  const CLI::App* Command(const std::string& name) const { return name.empty() ? &app_ : app_.get_subcommand(name); }
  // Every named (not positional) option of `command`, by Option::get_name().
  std::set<std::string> Of(const std::string& command) const {
    std::set<std::string> names;
    for (const CLI::Option* o : Command(command)->get_options()) {
      if (o->nonpositional()) names.insert(o->get_name());
    }
    return names;
  }
  const CLI::Option* Find(const std::string& command, const std::string& token) const {
    if (token.size() < 2 || token[0] != '-' || (token[1] >= '0' && token[1] <= '9')) return nullptr;
    return Command(command)->get_option_no_throw(token);
  }

 private:
  CLI::App app_;
  bool quiet_ = false;
  std::vector<hoilcd::Command> commands_;
};

// `base` with `extra` added: at the end (the command's flags) or, for hoilcd's own flags, first. A
// single-valued option of `extra` replaces the same option in `base`.
Args Merge(const Flags& flags, const Mode& mode, const Args& base, const Args& extra) {
  std::set<const CLI::Option*> replaced;
  for (const std::string& token : extra) {
    const CLI::Option* o = flags.Find(mode.command, token);
    if (o != nullptr && o->get_items_expected_max() <= 1) replaced.insert(o);
  }
  Args out;
  for (size_t i = 0; i < base.size(); ++i) {
    const CLI::Option* o = flags.Find(mode.command, base[i]);
    if (o != nullptr && replaced.count(o)) {
      i += static_cast<size_t>(o->get_items_expected_max());  // and its value
      continue;
    }
    out.push_back(base[i]);
  }
  if (mode.command.empty()) {
    out.insert(out.begin(), extra.begin(), extra.end());
  } else {
    out.insert(out.end(), extra.begin(), extra.end());
  }
  return out;
}

// `base` without `flag` (and its value).
Args Without(const Flags& flags, const Mode& mode, const Args& base, const std::string& flag) {
  const CLI::Option* target = flags.Find(mode.command, flag);
  Args out;
  for (size_t i = 0; i < base.size(); ++i) {
    const CLI::Option* o = flags.Find(mode.command, base[i]);
    if (o != nullptr && o == target) {
      i += static_cast<size_t>(std::max(0, std::min(1, o->get_items_expected_max())));
      continue;
    }
    out.push_back(base[i]);
  }
  return out;
}

// Every mode of every command and the rows of its flags.
std::vector<Mode> Modes() {
  const std::string scene = Source("tests/data/tiny_room.json");
  const std::string report = "{out}/r/report.json";
  const Probe help = Out();
  // The bench's flags, offline: the methods' figures change, or the flag is refused.
  const auto bench_rows = [&](const std::string& report_json, const std::string& method) {
    const Probe metrics = Metrics(report_json, method);
    const Probe labels = Json(report_json, {"/label_agreement"});
    return std::vector<Row>{
        {"--methods", {"--methods", "thumb,slcd"}, Expect::kActs, Json(report_json, {"/methods/slcd/mrr"})},
        {"--protocol", {"--protocol", "revisit"}, Expect::kActs, metrics},
        {"--radius", {"--radius", "0.6"}, Expect::kActs, metrics},
        {"--exclusion-window", {"--exclusion-window", "30"}, Expect::kActs, metrics},
        {"--ground-truth", {"--ground-truth", "true"}, Expect::kActs, metrics},
        {"--heading-tolerance", {"--heading-tolerance", "5"}, Expect::kActs, metrics},
        {"--overlap-threshold", {"--overlap-threshold", "0.9"}, Expect::kRefused},
        {"--overlap-threshold", {"--overlap-threshold", "0.9"}, Expect::kActs, labels, {"--ground-truth", "overlap"}},
        {"--overlap-stride", {"--overlap-stride", "16"}, Expect::kRefused},
        {"--overlap-stride", {"--overlap-stride", "16"}, Expect::kActs, labels, {"--ground-truth", "overlap"}},
        {"--overlap-depth-tolerance", {"--overlap-depth-tolerance", "0.5"}, Expect::kRefused},
        {"--overlap-depth-tolerance",
         {"--overlap-depth-tolerance", "0.5"},
         Expect::kActs,
         labels,
         {"--ground-truth", "overlap"}},
        {"--strata", {"--strata", "lap"}, Expect::kActs, Json(report_json, {"/strata"})},
        {"--param", {"--param", "thumbnail.width_px=8"}, Expect::kActs, metrics},
        {"--detector", {"--detector", "fast"}, Expect::kRefused},
        {"--detector", {"--detector", "fast"}, Expect::kActs, Json(report_json, {"/features"}), {"--methods", "slcd"}},
        {"--slam", {"--slam"}, Expect::kActs, Json(report_json, {"/slam"})},
        {"--slam-backend", {"--slam-backend", "cauchy"}, Expect::kRefused},
        {"--slam-backend",
         {"--slam-backend", "cauchy"},
         Expect::kActs,
         Json(report_json, {"/slam/backend"}),
         {"--slam"}},
        {"--loop-threshold", {"--loop-threshold", "5"}, Expect::kRefused},
        {"--loop-threshold",
         {"--loop-threshold", "5"},
         Expect::kActs,
         Json(report_json, {"/methods/" + method + "/slam"}),
         {"--slam"}},
        {"--baseline", {"--baseline", "{better}"}, Expect::kActs, Exit()},
        {"--max-drop", {"--max-drop", "1"}, Expect::kActs, OutLines("regression"), {"--baseline", "{better}"}},
        {"--junit", {"--junit", "{out}/junit.xml"}, Expect::kActs, Exists("{out}/junit.xml")},
    };
  };
  std::vector<Mode> modes;

  {
    Mode m{"hoilcd", "", {"generate", "--layout", "lounge", "-o", "{out}/g"}, {}, {}};
    m.rows = {{"--help", {"--help"}, Expect::kActs, help},
              {"--version", {"--version"}, Expect::kActs, help},
              {"--quiet", {"--quiet"}, Expect::kActs, Err()}};
    modes.push_back(m);
  }
  modes.push_back({"validate",
                   "validate",
                   {"-q", "validate", scene},
                   {},
                   {{"--help", {"--help"}, Expect::kActs, help},
                    {"--set", {"--set", "name=other"}, Expect::kActs, Out()},
                    {"--seed", {"--seed", "7"}, Expect::kActs, Out()}}});
  {
    const Probe manifest =
        Json("{out}/d/manifest.json", {"/scene_hash", "/seed", "/frame_count", "/outputs", "/shard"});
    modes.push_back({"render",
                     "render",
                     {"-q", "render", scene, "-o", "{out}/d", "--frames", "3"},
                     {},
                     {{"--help", {"--help"}, Expect::kActs, help},
                      {"--set", {"--set", "crowd.people_per_table=2"}, Expect::kActs, manifest},
                      {"--seed", {"--seed", "7"}, Expect::kActs, manifest},
                      {"--output", {}, Expect::kRequired},
                      {"--frames", {"--frames", "2"}, Expect::kActs, manifest},
                      {"--threads", {}, Expect::kThreads},
                      {"--shard", {"--shard", "0/2"}, Expect::kActs, manifest},
                      {"--outputs", {"--outputs", "thermal"}, Expect::kActs, manifest}}});
  }
  modes.push_back({"merge",
                   "merge",
                   {"-q", "merge", "{shard0}", "{shard1}", "-o", "{out}/m"},
                   {kShards},
                   {{"--help", {"--help"}, Expect::kActs, help},
                    {"--output", {}, Expect::kRequired},
                    {"--threads", {}, Expect::kThreads}}});
  {
    Mode m{"bench",
           "bench",
           {"-q", "bench", "{dataset}", "-o", "{out}/r", "--methods", "thumb"},
           {kDataset, kBaselines},
           {}};
    m.rows = bench_rows(report, "thumb");
    m.rows.insert(
        m.rows.end(),
        {{"--help", {"--help"}, Expect::kActs, help},
         {"--output", {}, Expect::kActs, Exists(report)},
         {"--threads", {}, Expect::kThreads},
         {"--dump-scores", {"--dump-scores", "{out}/scores"}, Expect::kActs, Exists("{out}/scores/thumb.csv")},
         {"--online", {"--online"}, Expect::kActs, Json(report, {"/mode"}), {"--methods", "slcd"}},
         {"--shortlist-k", {"--shortlist-k", "5"}, Expect::kRefused},
         {"--shortlist-index", {"--shortlist-index", "flat"}, Expect::kRefused},
         {"--shortlist-search-depth", {"--shortlist-search-depth", "8"}, Expect::kRefused}});
    modes.push_back(m);
  }
  {
    Mode m{"bench --online",
           "bench",
           {"-q", "bench", "{dataset}", "-o", "{out}/r", "--online", "--methods", "slcd"},
           {kDataset, kBaselines},
           {}};
    const Probe metrics = Metrics(report, "slcd");
    const Probe online = Json(report, {"/online/shortlist_hits", "/online/index_bytes", "/methods/slcd/mrr"});
    m.rows = {
        {"--help", {"--help"}, Expect::kActs, help},
        {"--output", {}, Expect::kActs, Exists(report)},
        {"--threads", {}, Expect::kThreads},
        {"--dump-scores", {"--dump-scores", "{out}/scores"}, Expect::kRefused},
        {"--online", {}, Expect::kActs, Json(report, {"/mode"})},
        {"--shortlist-k", {"--shortlist-k", "2"}, Expect::kActs, online},
        {"--shortlist-index", {"--shortlist-index", "flat"}, Expect::kActs, online},
        {"--shortlist-search-depth",
         {"--shortlist-search-depth", "8"},
         Expect::kActs,
         Json(report, {"/online/shortlist"})},
        {"--shortlist-search-depth",
         {"--shortlist-search-depth", "8"},
         Expect::kRefused,
         nullptr,
         {"--shortlist-index", "flat"}},
        {"--methods", {"--methods", "dlcd"}, Expect::kActs, Json(report, {"/methods/dlcd/mrr"})},
        {"--protocol", {"--protocol", "revisit"}, Expect::kActs, metrics},
        {"--radius", {"--radius", "0.6"}, Expect::kActs, metrics},
        {"--exclusion-window", {"--exclusion-window", "30"}, Expect::kActs, metrics},
        {"--ground-truth", {"--ground-truth", "true"}, Expect::kActs, metrics},
        {"--heading-tolerance", {"--heading-tolerance", "5"}, Expect::kActs, metrics},
        {"--overlap-threshold", {"--overlap-threshold", "0.9"}, Expect::kRefused},
        {"--overlap-stride", {"--overlap-stride", "16"}, Expect::kRefused},
        {"--overlap-depth-tolerance", {"--overlap-depth-tolerance", "0.5"}, Expect::kRefused},
        {"--strata", {"--strata", "lap"}, Expect::kRefused},
        {"--param", {"--param", "slcd.ransac_trials=5"}, Expect::kActs, metrics},
        {"--detector", {"--detector", "fast"}, Expect::kActs, metrics},
        {"--slam", {"--slam"}, Expect::kRefused},
        {"--slam-backend", {"--slam-backend", "cauchy"}, Expect::kRefused},
        {"--loop-threshold", {"--loop-threshold", "5"}, Expect::kRefused},
        {"--baseline", {"--baseline", "{better_online}"}, Expect::kActs, Exit()},
        {"--max-drop", {"--max-drop", "1"}, Expect::kActs, OutLines("regression"), {"--baseline", "{better_online}"}},
        {"--junit", {"--junit", "{out}/junit.xml"}, Expect::kActs, Exists("{out}/junit.xml")}};
    modes.push_back(m);
  }
  {
    const std::string evaluated = "{out}/e/report.json";
    const Probe metrics = Metrics(evaluated, "thumb");
    const Probe labels = Json(evaluated, {"/label_agreement"});
    modes.push_back(
        {"evaluate",
         "evaluate",
         {"-q", "evaluate", "{dataset}", "--scores", "{scores}", "-o", "{out}/e"},
         {kDataset, kScores, kBaselines},
         {{"--help", {"--help"}, Expect::kActs, help},
          {"--scores", {}, Expect::kRequired},
          {"--name", {"--name", "mine"}, Expect::kActs, Json(evaluated, {"/methods/mine/mrr"})},
          {"--output", {}, Expect::kActs, Exists(evaluated)},
          {"--protocol", {"--protocol", "revisit"}, Expect::kActs, metrics},
          {"--radius", {"--radius", "0.6"}, Expect::kActs, metrics},
          {"--exclusion-window", {"--exclusion-window", "30"}, Expect::kActs, metrics},
          {"--ground-truth", {"--ground-truth", "true"}, Expect::kActs, metrics},
          {"--heading-tolerance", {"--heading-tolerance", "5"}, Expect::kActs, metrics},
          {"--overlap-threshold", {"--overlap-threshold", "0.9"}, Expect::kRefused},
          {"--overlap-threshold", {"--overlap-threshold", "0.9"}, Expect::kActs, labels, {"--ground-truth", "overlap"}},
          {"--overlap-stride", {"--overlap-stride", "16"}, Expect::kRefused},
          {"--overlap-stride", {"--overlap-stride", "16"}, Expect::kActs, labels, {"--ground-truth", "overlap"}},
          {"--overlap-depth-tolerance", {"--overlap-depth-tolerance", "0.5"}, Expect::kRefused},
          {"--overlap-depth-tolerance",
           {"--overlap-depth-tolerance", "0.5"},
           Expect::kActs,
           labels,
           {"--ground-truth", "overlap"}},
          {"--baseline", {"--baseline", "{better}"}, Expect::kActs, Exit()},
          {"--max-drop", {"--max-drop", "1"}, Expect::kActs, OutLines("regression"), {"--baseline", "{better}"}},
          {"--junit", {"--junit", "{out}/junit.xml"}, Expect::kActs, Exists("{out}/junit.xml")}}});
  }
  modes.push_back({"inspect",
                   "inspect",
                   {"-q", "inspect", "{dataset}", "--json"},
                   {kDataset},
                   {{"--help", {"--help"}, Expect::kActs, help},
                    {"--json", {}, Expect::kActs, Out()},
                    {"--output", {"-o", "{out}/i"}, Expect::kActs, Exists("{out}/i/inspect.json")},
                    {"--protocol", {"--protocol", "revisit"}, Expect::kActs, Out()},
                    {"--radius", {"--radius", "0.6"}, Expect::kActs, Out()}}});
  {
    const Probe files = Files("{out}/g");
    modes.push_back({"generate",
                     "generate",
                     {"-q", "generate", "--layout", "lounge", "--count", "2", "-o", "{out}/g"},
                     {},
                     {{"--help", {"--help"}, Expect::kActs, help},
                      {"--layout", {"--layout", "office"}, Expect::kActs, files},
                      {"--count", {"--count", "3"}, Expect::kActs, files},
                      {"--start", {"--start", "4"}, Expect::kActs, files},
                      {"--seed", {"--seed", "7"}, Expect::kActs, files},
                      {"--output", {}, Expect::kRequired},
                      {"--set", {"--set", "occupancy_min=0.9"}, Expect::kActs, files},
                      {"--threads", {}, Expect::kThreads}}});
  }
  modes.push_back({"export-mot",
                   "export-mot",
                   {"-q", "export-mot", "{dataset}", "-o", "{out}/x"},
                   {kDataset},
                   {{"--help", {"--help"}, Expect::kActs, help},
                    {"--output", {}, Expect::kRequired},
                    {"--threads", {}, Expect::kThreads}}});
  modes.push_back({"export-coco",
                   "export-coco",
                   {"-q", "export-coco", "{dataset}", "-o", "{out}/x"},
                   {kDataset},
                   {{"--help", {"--help"}, Expect::kActs, help}, {"--output", {}, Expect::kRequired}}});
  {
    const Probe bag = [](const CommandRun& r) { return TextOf(r.out + "/x.mcap"); };
    modes.push_back({"export-mcap",
                     "export-mcap",
                     {"-q", "export-mcap", "{dataset}", "-o", "{out}/x.mcap"},
                     {kDataset},
                     {{"--help", {"--help"}, Expect::kActs, help},
                      {"--output", {}, Expect::kRequired},
                      {"--compression", {"--compression", "none"}, Expect::kActs, bag},
                      {"--threads", {}, Expect::kThreads}}});
  }
  modes.push_back({"params", "params", {"-q", "params"}, {}, {{"--help", {"--help"}, Expect::kActs, help}}});
  {
    // The dataset's own radiometric frames (16-bit centikelvin) serve as the "real" folder.
    const Probe report = [](const CommandRun& r) { return TextOf(r.out + "/r/realism.json"); };
    modes.push_back({"realism",
                     "realism",
                     {"-q", "realism", "{dataset}", "{dataset}/radiometric", "-o", "{out}/r", "--scale", "0.01",
                      "--offset", "-273.15"},
                     {kDataset},
                     {{"--help", {"--help"}, Expect::kActs, help},
                      {"--output", {}, Expect::kRequired},
                      {"--stride", {"--stride", "2"}, Expect::kActs, report},
                      {"--scale", {}, Expect::kActs, Exit()},  // 16-bit frames without it are refused
                      {"--offset", {}, Expect::kActs, Exit()},
                      {"--float-unit", {"--float-unit", "k"}, Expect::kRefused},
                      {"--static", {"--static"}, Expect::kActs, report},
                      {"--threads", {}, Expect::kThreads}}});
  }
  modes.push_back(
      {"reference", "reference", {"-q", "reference", "cameras"}, {}, {{"--help", {"--help"}, Expect::kActs, help}}});

  // The commands that render and bench (30 frames: no true match, so the protocol's flags show in
  // what each report says it ran with).
  const auto pipeline_rows = [&](const std::string& report_json) {
    const Probe settings = Json(report_json, {"/protocol", "/methods/thumb/queries_scored", "/parameters"});
    return std::vector<Row>{
        {"--methods", {"--methods", "thumb,slcd"}, Expect::kActs, Json(report_json, {"/methods/slcd"})},
        {"--protocol", {"--protocol", "revisit"}, Expect::kActs, settings},
        {"--radius", {"--radius", "0.6"}, Expect::kActs, settings},
        {"--exclusion-window", {"--exclusion-window", "1"}, Expect::kActs, settings},
        {"--ground-truth", {"--ground-truth", "true"}, Expect::kActs, settings},
        {"--heading-tolerance", {"--heading-tolerance", "5"}, Expect::kActs, settings},
        {"--overlap-threshold", {"--overlap-threshold", "0.9"}, Expect::kRefused},
        {"--overlap-threshold", {"--overlap-threshold", "0.9"}, Expect::kActs, settings, {"--ground-truth", "overlap"}},
        {"--overlap-stride", {"--overlap-stride", "16"}, Expect::kRefused},
        {"--overlap-stride", {"--overlap-stride", "16"}, Expect::kActs, settings, {"--ground-truth", "overlap"}},
        {"--overlap-depth-tolerance", {"--overlap-depth-tolerance", "0.5"}, Expect::kRefused},
        {"--overlap-depth-tolerance",
         {"--overlap-depth-tolerance", "0.5"},
         Expect::kActs,
         settings,
         {"--ground-truth", "overlap"}},
        // A few queries of the revisit protocol in 30 frames, so that there are strata to report.
        {"--strata",
         {"--strata", "lap"},
         Expect::kActs,
         Json(report_json, {"/strata"}),
         {"--protocol", "revisit", "--exclusion-window", "0.5"}},
        {"--param", {"--param", "thumbnail.width_px=8"}, Expect::kActs, settings},
        {"--detector", {"--detector", "fast"}, Expect::kRefused},
        {"--detector", {"--detector", "fast"}, Expect::kActs, settings, {"--methods", "slcd"}},
        {"--slam", {"--slam", "--loop-threshold", "5"}, Expect::kActs, Json(report_json, {"/slam/backend"})},
        {"--slam-backend", {"--slam-backend", "cauchy"}, Expect::kRefused},
        {"--slam-backend",
         {"--slam-backend", "cauchy"},
         Expect::kActs,
         Json(report_json, {"/slam/backend"}),
         {"--slam", "--loop-threshold", "5"}},
        {"--loop-threshold", {"--loop-threshold", "5"}, Expect::kRefused},
        {"--loop-threshold",
         {"--loop-threshold", "7"},
         Expect::kActs,
         Json(report_json, {"/methods/thumb/slam"}),
         {"--slam", "--loop-threshold", "5"}},
    };
  };
  // A merge given the sweep or suite too checks that the shards ran it: each bench flag acts when it
  // changes what was run (the merge then refuses the shards, saying what differs). The shards were
  // run with kRichBench, so every bench flag applies.
  const auto spec_merge_rows = [&](const Probe& acted) {
    return std::vector<Row>{
        {"--methods", {"--methods", "slcd,thumb"}, Expect::kActs, acted},
        {"--protocol", {"--protocol", "revisit"}, Expect::kActs, acted},
        {"--radius", {"--radius", "0.6"}, Expect::kActs, acted},
        {"--exclusion-window", {"--exclusion-window", "1"}, Expect::kActs, acted},
        {"--ground-truth", {"--ground-truth", "true"}, Expect::kActs, acted},
        {"--heading-tolerance", {"--heading-tolerance", "5"}, Expect::kActs, acted},
        {"--overlap-threshold", {"--overlap-threshold", "0.9"}, Expect::kActs, acted},
        {"--overlap-threshold",
         {"--overlap-threshold", "0.9"},
         Expect::kRefused,
         nullptr,
         {"--ground-truth", "odometry"}},
        {"--overlap-stride", {"--overlap-stride", "16"}, Expect::kActs, acted},
        {"--overlap-stride", {"--overlap-stride", "16"}, Expect::kRefused, nullptr, {"--ground-truth", "odometry"}},
        {"--overlap-depth-tolerance", {"--overlap-depth-tolerance", "0.5"}, Expect::kActs, acted},
        {"--overlap-depth-tolerance",
         {"--overlap-depth-tolerance", "0.5"},
         Expect::kRefused,
         nullptr,
         {"--ground-truth", "odometry"}},
        {"--strata", {"--strata", "lap"}, Expect::kActs, acted},
        {"--param", {"--param", "slcd.ransac_trials=5"}, Expect::kActs, acted},
        {"--detector", {"--detector", "fast"}, Expect::kActs, acted},
        {"--detector", {"--detector", "fast"}, Expect::kRefused, nullptr, {"--methods", "thumb"}},
        {"--slam", {}, Expect::kActs, acted},
        {"--slam-backend", {"--slam-backend", "cauchy"}, Expect::kActs, acted},
        {"--slam-backend", {"--slam-backend", "cauchy"}, Expect::kRefused, nullptr, {"--no-slam"}},
        {"--loop-threshold", {"--loop-threshold", "7"}, Expect::kActs, acted},
        {"--loop-threshold", {"--loop-threshold", "5"}, Expect::kRefused, nullptr, {"--no-slam"}},
    };
  };
  {
    const std::string run_report = "{out}/r/report.json";
    Mode m{"run",
           "run",
           {"-q", "run", scene, "--set", "frames=30", "--cache", "{cache}", "-o", "{out}/r", "--methods", "thumb",
            "--no-slam"},
           {kBaselines},
           pipeline_rows(run_report)};
    m.rows.insert(
        m.rows.end(),
        {{"--help", {"--help"}, Expect::kActs, help},
         {"--set", {"--set", "crowd.people_per_table=2"}, Expect::kActs, Json(run_report, {"/dataset"})},
         {"--seed", {"--seed", "7"}, Expect::kActs, Json(run_report, {"/dataset"})},
         {"--cache", {"--cache", "{out}/cache"}, Expect::kActs, Exists("{out}/cache")},
         {"--output", {"-o", "{out}/elsewhere"}, Expect::kActs, Exists("{out}/elsewhere/report.json")},
         {"--threads", {}, Expect::kThreads},
         {"--baseline", {"--baseline", "{better}"}, Expect::kActs, Exit()},
         {"--max-drop", {"--max-drop", "1"}, Expect::kActs, OutLines("regression"), {"--baseline", "{better}"}},
         {"--junit", {"--junit", "{out}/junit.xml"}, Expect::kActs, Exists("{out}/junit.xml")}});
    modes.push_back(m);
  }
  {
    const std::string run_report = "{out}/s/runs/frames=30,seed=1/report.json";
    Mode m{"sweep",
           "sweep",
           {"-q", "sweep", scene, "--set", "frames=30", "--cache", "{cache}", "-o", "{out}/s", "--methods", "thumb"},
           {},
           pipeline_rows(run_report)};
    m.rows.insert(m.rows.end(),
                  {{"--help", {"--help"}, Expect::kActs, help},
                   {"--set", {"--set", "crowd.people_per_table=2"}, Expect::kActs, Files("{out}/s/runs")},
                   {"--seeds", {"--seeds", "2"}, Expect::kActs, Files("{out}/s/runs")},
                   {"--cache", {"--cache", "{out}/cache"}, Expect::kActs, Exists("{out}/cache")},
                   {"--drop-datasets",
                    {"--drop-datasets", "--cache", "{out}/cache"},
                    Expect::kActs,
                    Files("{out}/cache"),
                    {"--cache", "{out}/cache"}},
                   {"--output", {}, Expect::kRequired},
                   {"--shard", {"--shard", "1/2"}, Expect::kActs, Files("{out}/s/runs")},
                   {"--merge", {"--merge", "{sweep_output}"}, Expect::kActs, Exists("{out}/s/summary.csv")},
                   {"--threads", {}, Expect::kThreads}});
    modes.push_back(m);
  }
  {
    // --merge without SCENE: only the shards are read.
    Mode m{"sweep --merge", "sweep", {"-q", "sweep", "--merge", "{sweep_output}", "-o", "{out}/s"}, {kSweepOutput}, {}};
    for (const Row& r : pipeline_rows("")) m.rows.push_back({r.flag, r.args, Expect::kRefused});
    m.rows.insert(m.rows.end(), {{"--help", {"--help"}, Expect::kActs, help},
                                 {"--set", {"--set", "frames=30"}, Expect::kRefused},
                                 {"--seeds", {"--seeds", "1"}, Expect::kRefused},
                                 {"--cache", {"--cache", "{cache}"}, Expect::kRefused},
                                 {"--drop-datasets", {"--drop-datasets"}, Expect::kRefused},
                                 {"--output", {}, Expect::kRequired},
                                 {"--shard", {"--shard", "0/2"}, Expect::kRefused},
                                 {"--merge", {}, Expect::kActs, Exists("{out}/s/summary.csv")},
                                 {"--threads", {"--threads", "2"}, Expect::kRefused}});
    modes.push_back(m);
  }
  {
    // --merge with SCENE: the flags are checked against what the shards ran.
    Args base = {"-q", "sweep", scene, "--set", "frames=30", "--merge", "{sweep_output}", "-o", "{out}/s"};
    base.insert(base.end(), kRichBench.begin(), kRichBench.end());
    Mode m{"sweep SCENE --merge", "sweep", base, {kSweepOutput}, spec_merge_rows(Err())};
    m.rows.insert(m.rows.end(), {{"--help", {"--help"}, Expect::kActs, help},
                                 {"--set", {"--set", "crowd.people_per_table=2"}, Expect::kActs, Err()},
                                 {"--seeds", {"--seeds", "2"}, Expect::kActs, Err()},
                                 {"--cache", {"--cache", "{cache}"}, Expect::kRefused},
                                 {"--drop-datasets", {"--drop-datasets"}, Expect::kRefused},
                                 {"--output", {}, Expect::kRequired},
                                 {"--shard", {"--shard", "0/2"}, Expect::kRefused},
                                 {"--merge", {}, Expect::kActs, Exists("{out}/s/sweep.json")},
                                 {"--threads", {"--threads", "2"}, Expect::kRefused}});
    modes.push_back(m);
  }
  {
    const std::string run_report = "{out}/s/runs/tiny-seed1/report.json";
    Mode m{"suite",
           "suite",
           {"-q", "suite", "{suite}", "--cache", "{cache}", "-o", "{out}/s", "--methods", "thumb"},
           {kSuiteFiles},
           pipeline_rows(run_report)};
    m.rows.insert(m.rows.end(), {{"--help", {"--help"}, Expect::kActs, help},
                                 {"--output", {}, Expect::kRequired},
                                 {"--split", {"--split", "test"}, Expect::kActs, Exit()},
                                 {"--cache", {"--cache", "{out}/cache"}, Expect::kActs, Exists("{out}/cache")},
                                 {"--drop-datasets",
                                  {"--drop-datasets", "--cache", "{out}/cache"},
                                  Expect::kActs,
                                  Files("{out}/cache"),
                                  {"--cache", "{out}/cache"}},
                                 {"--shard", {"--shard", "1/2"}, Expect::kActs, Exists("{out}/s/suite_report.json")},
                                 {"--merge", {"--merge", "{suite_output}"}, Expect::kActs, Exists("{out}/s/runs")},
                                 {"--threads", {}, Expect::kThreads}});
    modes.push_back(m);
  }
  {
    Mode m{"suite --merge", "suite", {"-q", "suite", "--merge", "{suite_output}", "-o", "{out}/s"}, {kSuiteOutput}, {}};
    for (const Row& r : pipeline_rows("")) m.rows.push_back({r.flag, r.args, Expect::kRefused});
    m.rows.insert(m.rows.end(), {{"--help", {"--help"}, Expect::kActs, help},
                                 {"--output", {}, Expect::kRequired},
                                 {"--split", {"--split", "dev"}, Expect::kRefused},
                                 {"--cache", {"--cache", "{cache}"}, Expect::kRefused},
                                 {"--drop-datasets", {"--drop-datasets"}, Expect::kRefused},
                                 {"--shard", {"--shard", "0/2"}, Expect::kRefused},
                                 {"--merge", {}, Expect::kActs, Exists("{out}/s/suite_report.json")},
                                 {"--threads", {"--threads", "2"}, Expect::kRefused}});
    modes.push_back(m);
  }
  {
    Args base = {"-q", "suite", "{failing_suite}", "--merge", "{suite_output}", "-o", "{out}/s"};
    base.insert(base.end(), kRichBench.begin(), kRichBench.end());
    Mode m{"suite SUITE --merge", "suite", base, {kSuiteOutput}, spec_merge_rows(Err())};
    m.rows.insert(m.rows.end(), {{"--help", {"--help"}, Expect::kActs, help},
                                 {"--output", {}, Expect::kRequired},
                                 {"--split", {"--split", "dev"}, Expect::kActs, Err()},
                                 {"--cache", {"--cache", "{cache}"}, Expect::kRefused},
                                 {"--drop-datasets", {"--drop-datasets"}, Expect::kRefused},
                                 {"--shard", {"--shard", "0/2"}, Expect::kRefused},
                                 {"--merge", {}, Expect::kActs, Exists("{out}/s/suite.json")},
                                 {"--threads", {"--threads", "2"}, Expect::kRefused}});
    modes.push_back(m);
  }
  return modes;
}

const Mode& ModeNamed(const std::string& name) {
  static const std::vector<Mode> modes = Modes();
  for (const Mode& m : modes) {
    if (m.name == name) return m;
  }
  ADD_FAILURE() << "no mode " << name;
  return modes.front();
}

// The files a mode's command lines name, made in `temp`; the placeholders that stand for them.
std::map<std::string, std::string> MakeFixtures(const Mode& mode, const test::TestDir& temp) {
  std::map<std::string, std::string> vars = {{"{cache}", temp / "cache"}};
  const std::string tiny = Source("tests/data/tiny_room.json");
  std::set<Fixture> needed = mode.fixtures;
  if (needed.count(kScores)) needed.insert(kDataset);
  if (needed.count(kDataset)) vars["{dataset}"] = test::RenderTinyRoom(temp / "dataset");
  if (needed.count(kScores)) {
    const test::CliOutcome o = test::RunCli({"bench", vars["{dataset}"], "--methods", "thumb", "-o",
                                             temp / "scores_report", "--dump-scores", temp / "scores"});
    EXPECT_EQ(o.exit_code, 0) << o.err;
    vars["{scores}"] = temp / "scores/thumb.csv";
  }
  if (needed.count(kBaselines)) {
    for (const auto& [name, method, mode_key] : std::vector<std::tuple<std::string, std::string, std::string>>{
             {"better", "thumb", ""}, {"better_online", "slcd", "online"}}) {
      nlohmann::json report = {{"methods", {{method, {{"mrr", 0.99}, {"recall_at_1", 0.99}}}}}};
      if (!mode_key.empty()) report["mode"] = mode_key;
      WriteFileAtomic(temp / (name + ".json"), report.dump());
      vars["{" + name + "}"] = temp / (name + ".json");
    }
  }
  if (needed.count(kShards)) {
    for (const char* shard : {"0", "1"}) {
      const test::CliOutcome o = test::RunCli({"render", tiny, "-o", temp / ("shard" + std::string(shard)), "--frames",
                                               "16", "--shard", std::string(shard) + "/2"});
      EXPECT_EQ(o.exit_code, 0) << o.err;
      vars["{shard" + std::string(shard) + "}"] = temp / ("shard" + std::string(shard));
    }
  }
  if (needed.count(kSweepOutput)) {
    Args args = {"sweep", tiny, "--set", "frames=30", "--cache", temp / "cache", "-o", temp / "sweep_output"};
    args.insert(args.end(), kRichBench.begin(), kRichBench.end());
    const test::CliOutcome o = test::RunCli(args);
    EXPECT_EQ(o.exit_code, 0) << o.err;
  }
  vars["{sweep_output}"] = temp / "sweep_output";
  WriteFileAtomic(temp / "suite.json", R"({"name": "tiny", "sequences": [
      {"name": "tiny", "scene": ")" + tiny +
                                           R"(", "seeds": [1], "split": "dev", "set": ["frames=30"]}]})");
  vars["{suite}"] = temp / "suite.json";
  WriteFileAtomic(temp / "failing.json", R"({"name": "failing", "sequences": [
      {"name": "a", "scene": "no_a.json", "seeds": [1], "split": "dev"},
      {"name": "b", "scene": "no_b.json", "seeds": [1], "split": "test"}]})");
  vars["{failing_suite}"] = temp / "failing.json";
  if (needed.count(kSuiteOutput)) {
    Args args = {"suite", temp / "failing.json", "-o", temp / "suite_output"};
    args.insert(args.end(), kRichBench.begin(), kRichBench.end());
    const test::CliOutcome o = test::RunCli(args);
    EXPECT_EQ(o.exit_code, 1) << o.err;  // its runs fail (no scene files) and are listed: a merge reads them
  }
  vars["{suite_output}"] = temp / "suite_output";
  return vars;
}

class EveryFlag : public testing::TestWithParam<std::string> {};

// Gives each flag of the mode as its row says, and checks the command acted on it or refused it.
TEST_P(EveryFlag, ChangesWhatTheCommandDoesOrIsRefusedByName) {
  const Mode& mode = ModeNamed(GetParam());
  const Flags flags;
  const test::TestDir temp;
  const std::map<std::string, std::string> vars = MakeFixtures(mode, temp);
  int runs = 0;
  std::map<Args, CommandRun> done;  // a command line given twice runs once (the runs without a flag repeat)
  const auto invoke = [&](const Args& args) {
    if (const auto it = done.find(args); it != done.end()) return it->second;
    CommandRun& run = done[args];
    run.out = temp / ("run" + std::to_string(runs++));
    Args resolved;
    for (std::string a : args) {
      a = Replace(a, "{out}", run.out);
      for (const auto& [from, to] : vars) a = Replace(a, from, to);
      resolved.push_back(a);
    }
    run.outcome = Invoke(resolved);
    return run;
  };
  const auto line = [](const Args& args) {
    std::string text;
    for (const std::string& a : args) text += " " + a;
    return text;
  };
  for (const Row& row : mode.rows) {
    SCOPED_TRACE(mode.name + ": " + row.flag + line(row.args) +
                 (row.context.empty() ? "" : " with" + line(row.context)));
    const Args base = Merge(flags, mode, mode.base, row.context);
    switch (row.expect) {
      case Expect::kActs: {
        const Args with = row.args.empty() ? base : Merge(flags, mode, base, row.args);
        const Args without = row.args.empty() ? Without(flags, mode, base, row.flag) : base;
        const CommandRun a = invoke(without), b = invoke(with);
        const std::string before = row.probe(a), after = row.probe(b);
        EXPECT_NE(before, after) << "the flag changed nothing: " << line(with) << "\n"
                                 << after << "\nerr: " << b.outcome.err;
        break;
      }
      case Expect::kRefused: {
        const CommandRun r = invoke(Merge(flags, mode, base, row.args));
        EXPECT_NE(r.outcome.exit_code, 0) << r.outcome.out;
        EXPECT_NE(r.outcome.err.find(row.flag), std::string::npos) << r.outcome.err;
        break;
      }
      case Expect::kRequired: {
        const CLI::Option* option = flags.Find(mode.command, row.flag);
        ASSERT_NE(option, nullptr);
        EXPECT_TRUE(option->get_required());
        const CommandRun r = invoke(Without(flags, mode, base, row.flag));
        EXPECT_NE(r.outcome.exit_code, 0);
        EXPECT_NE(r.outcome.err.find(row.flag), std::string::npos) << r.outcome.err;
        break;
      }
      case Expect::kThreads: {
        CommandRun one, three;
        const int helpers_one = HelpersThatWorked([&] { one = invoke(Merge(flags, mode, base, {"--threads", "1"})); });
        const int helpers_three = HelpersThatWorked([&] {
          three = invoke(Merge(flags, mode, base, {"--threads", "3"}));
        });
        EXPECT_EQ(one.outcome.exit_code, 0) << one.outcome.err;
        EXPECT_EQ(three.outcome.exit_code, 0) << three.outcome.err;
        EXPECT_GT(helpers_three, helpers_one);
        break;
      }
    }
  }
}

std::vector<std::string> ModeNames() {
  std::vector<std::string> names;
  for (const Mode& m : Modes()) names.push_back(m.name);
  return names;
}

INSTANTIATE_TEST_SUITE_P(Modes, EveryFlag, testing::ValuesIn(ModeNames()), [](const auto& info) {
  std::string name = info.param;
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
});

// Every flag of every command, as the app lists it, has a row in each mode of its command; every
// command has a mode; no row names a flag the command does not have.
TEST(EveryFlagTable, EveryFlagOfEveryModeHasARow) {
  const Flags flags;
  std::set<std::string> commands_with_a_mode;
  for (const Mode& mode : Modes()) {
    commands_with_a_mode.insert(mode.command);
    std::set<std::string> rows;
    for (const Row& row : mode.rows) rows.insert(row.flag);
    const std::set<std::string> listed = flags.Of(mode.command);
    for (const std::string& flag : listed) EXPECT_TRUE(rows.count(flag)) << mode.name << ": no row for " << flag;
    for (const std::string& flag : rows) EXPECT_TRUE(listed.count(flag)) << mode.name << ": no flag " << flag;
  }
  const std::function<bool(const CLI::App*)> every = [](const CLI::App*) { return true; };
  for (const CLI::App* sub : flags.Command("")->get_subcommands(every)) {
    EXPECT_TRUE(commands_with_a_mode.count(sub->get_name())) << "no mode of hoilcd " << sub->get_name();
  }
}

}  // namespace
}  // namespace hoilcd
