#include "shared.h"

#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <set>

#include "hoilcd/bench/methods/front_ends.h"
#include "hoilcd/bench/methods/method_params.h"
#include "hoilcd/bench/methods/methods.h"
#include "hoilcd/bench/report/diagnosis.h"
#include "hoilcd/bench/report/gate.h"
#include "hoilcd/bench/report/report.h"
#include "hoilcd/bench/slam/pose_graph.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/file_io.h"
#include "hoilcd/core/util/safe_text.h"
#include "hoilcd/core/util/sizes.h"

namespace hoilcd {
namespace {

constexpr int kMaxThreadsFlag = 1024;  // --threads accepts this much (ParallelFor clamps to kMaxThreads)

std::atomic<bool> g_interrupted{false};

extern "C" void OnInterrupt(int) {
  g_interrupted = true;
  std::signal(SIGINT, SIG_DFL);  // a second Ctrl-C ends the process at once
}

// Whether whole-number text is in `range`, compared exactly (a long double holds every 64-bit
// integer and every double): through a double, 2^53 + 1 would pass a maximum of 2^53 and then be
// used as itself. Text beyond 64 bits is outside any bound on its side.
bool WholeNumberIn(const std::string& text, const OptionRange& range) {
  errno = 0;
  char* end = nullptr;
  const bool negative = text[0] == '-';
  const long double value = negative ? static_cast<long double>(std::strtoll(text.c_str(), &end, 10))
                                     : static_cast<long double>(std::strtoull(text.c_str(), &end, 10));
  if (errno == ERANGE) return negative ? !range.min : !range.max;
  if (range.min && (range.min->exclusive ? !(value > range.min->value) : !(value >= range.min->value))) return false;
  if (range.max && (range.max->exclusive ? !(value < range.max->value) : !(value <= range.max->value))) return false;
  return true;
}

}  // namespace

CLI::Validator NumberIn(const OptionRange& range) {
  return CLI::Validator(
      [range](std::string& text) -> std::string {
        const char* begin = text.c_str();
        char* end = nullptr;
        const double value = std::strtod(begin, &end);
        const bool parsed = end != begin && *end == '\0';
        const size_t digits = text.find_first_not_of("0123456789", text[0] == '-' || text[0] == '+' ? 1 : 0);
        const bool whole = digits == std::string::npos && text.find_first_of("0123456789") != std::string::npos;
        if (whole ? WholeNumberIn(text, range) : parsed && std::isfinite(value) && range.Contains(value)) return "";
        const bool bounded = range.min || range.max;
        return std::string("expected ") + (bounded ? "a number " : "") + range.ToString() + ", got '" + text + "'";
      },
      range.ToString());
}

bool Given(const CLI::App& cmd, const std::string& flag) {
  const CLI::Option* option = cmd.get_option_no_throw(flag);
  HOILCD_CHECK_MSG(option != nullptr, "no flag " + flag + " on hoilcd " + cmd.get_name());
  return option->count() > 0;
}

void RefuseIfGiven(const CLI::App& cmd, const std::string& flag, const std::string& why) {
  if (Given(cmd, flag)) throw InputError(flag, why);
}

void AddThreadsFlag(CLI::App* cmd, int* threads) {
  cmd->add_option("--threads", *threads, "worker threads (0: the CPUs this process may use)")
      ->check(NumberIn(OptionRange::Closed(0, kMaxThreadsFlag)));
}

void AddShardFlag(CLI::App* cmd, std::optional<std::string>* shard, const std::string& description) {
  cmd->add_option_function<std::string>(
         "--shard", [shard](const std::string& text) { *shard = text; }, description)
      ->type_name("I/N");
}

void AddManyRunsCacheFlags(CLI::App* cmd, RunOptions* run) {
  cmd->add_option("--cache", run->cache_dir, "folder of cached datasets (shared by every run and shard)");
  cmd->add_flag(
      "--drop-datasets", [run](std::int64_t) { run->keep_datasets = false; },
      "delete each run's dataset once its report is written (a large suite or sweep needs ~1 GB of disk a "
      "thousand frames otherwise); reports are kept and a rerun keeps them");
}

void AddSceneFlags(CLI::App* cmd, SceneArgs* args, bool scene_required) {
  auto* opt = cmd->add_option("scene", args->path, "scene file (JSON, see scenes/scene.schema.json)");
  if (scene_required) opt->required();
  cmd->add_option("--set", args->overrides,
                  "override a scene value by its path, e.g. --set crowd.people_per_table=2 (repeatable)")
      ->type_name("KEY=VALUE");
  cmd->add_option("--seed", args->seed, "override the scene's seed")
      ->check(NumberIn(OptionRange::Closed(0, static_cast<double>(kMaxSeed))));
}

Scene LoadSceneArgs(const SceneArgs& args) {
  std::vector<std::string> overrides = args.overrides;
  if (args.seed >= 0) overrides.push_back("seed=" + std::to_string(args.seed));
  return LoadScene(args.path, overrides);
}

// Each flag's help shows its default, the value in the ProtocolOptions the command starts from.
void AddProtocolAndRadiusFlags(CLI::App* cmd, ProtocolOptions* protocol) {
  AddTableFlag(cmd, "--protocol", ProtocolOptions::Table().List(), "protocol", &protocol->protocol);
  cmd->add_option("--radius", protocol->radius_m, "true-match radius, m (the default is the paper's)")
      ->check(NumberIn(OptionRange().Above(0)))
      ->capture_default_str();
}

void AddProtocolFlags(CLI::App* cmd, ProtocolOptions* protocol) {
  AddProtocolAndRadiusFlags(cmd, protocol);
  cmd->add_option("--exclusion-window", protocol->exclusion_window_s,
                  "frames this close in time to a query are not in its database, s")
      ->check(NumberIn(OptionRange().AtLeast(0)))
      ->capture_default_str();
  cmd->add_option("--ground-truth", protocol->ground_truth,
                  "what labels true matches: odometry (positions, the paper's), true (true positions) or overlap "
                  "(the share of the query's static view the reference sees)")
      ->check(CLI::IsMember({"odometry", "true", "overlap"}))
      ->capture_default_str();
  AddTableFlag(cmd, "--overlap-threshold", ProtocolOptions::Table().List(), "overlap_threshold",
               &protocol->overlap_threshold);
  AddTableFlag(cmd, "--overlap-stride", ProtocolOptions::Table().List(), "overlap_stride_px",
               &protocol->overlap_stride_px);
  AddTableFlag(cmd, "--overlap-depth-tolerance", ProtocolOptions::Table().List(), "overlap_depth_tolerance_m",
               &protocol->overlap_depth_tolerance_m);
  cmd->add_option("--heading-tolerance", protocol->heading_tolerance_deg,
                  "max heading difference of a true match, deg (negative: off)")
      ->check(NumberIn(OptionRange()))
      ->capture_default_str();
}

void CheckProtocolFlagsApply(const CLI::App& cmd, const ProtocolOptions& protocol) {
  if (protocol.ground_truth == "overlap") return;
  for (const char* flag : {"--overlap-threshold", "--overlap-stride", "--overlap-depth-tolerance"}) {
    RefuseIfGiven(cmd, flag,
                  "applies to --ground-truth overlap only (the ground truth is " + protocol.ground_truth +
                      "); drop it or add --ground-truth overlap");
  }
}

void AddBenchFlags(CLI::App* cmd, BenchArgs* args) {
  const size_t before = cmd->get_options().size();
  cmd->add_option("--methods", args->methods,
                  "comma-separated methods, or 'paper' / 'all' (default: all; see the report)");
  AddProtocolFlags(cmd, &args->options.protocol);
  cmd->add_option("--strata", args->options.strata,
                  "conditions the report splits the metrics by, comma-separated: view, contrast, occlusion, "
                  "walkers, turning, lap, ffc (default: view,contrast,occlusion,walkers)")
      ->delimiter(',');
  cmd->add_option("--param", args->options.params,
                  "a parameter of one method or front end, e.g. slcd.ransac_trials=50, fusion.k=60, "
                  "persons.threshold_c=27 (repeatable; hoilcd params lists them)")
      ->type_name("NAME=VALUE");
  cmd->add_option("--detector", args->options.keypoints.detector, "SLCD keypoints: gftt, fast, orb, sift, akaze")
      ->check(CLI::IsMember({"gftt", "fast", "orb", "sift", "akaze"}));
  cmd->add_flag("--slam,!--no-slam", args->options.slam,
                "each method's loops in a pose graph: ATE/RPE per back end (default: on in run, off in bench)");
  cmd->add_option("--slam-backend", args->options.slam_options.slam.graph.backend,
                  "headline pose-graph back end: plain, cauchy or dcs (all three are reported)")
      ->check(CLI::IsMember(PoseGraphBackends()));
  cmd->add_option("--loop-threshold", args->options.slam_options.slam.loop_threshold,
                  "accept a method's top-1 match as a loop when its score is at least this (default: the "
                  "threshold of 100 % precision on the calibration sequence)")
      ->check(NumberIn(OptionRange()));
  args->cmd = cmd;
  const std::vector<CLI::Option*> options = cmd->get_options();
  for (size_t i = before; i < options.size(); ++i) args->flags.push_back(options[i]->get_name());
}

namespace {

// Whether a method of `methods`, or one it combines, reads one of `front_ends`.
bool UsesFrontEnd(const std::vector<std::string>& methods, const std::set<FrontEnd>& front_ends) {
  for (const std::string& m : methods) {
    const LoopClosureMethod& method = FindMethod(m);
    for (FrontEnd f : method.FrontEnds()) {
      if (front_ends.count(f)) return true;
    }
    if (UsesFrontEnd(method.Inputs(), front_ends)) return true;
  }
  return false;
}

}  // namespace

BenchOptions ResolveBench(const BenchArgs& args, int threads) {
  BenchOptions o = args.options;
  o.methods = args.methods.empty() ? DefaultMethods() : ParseMethodList(args.methods, &o.optional_methods);
  if (args.methods.empty()) o.optional_methods = o.methods;
  o.threads = threads;
  CheckParams(o.params, o.methods);
  if (const std::string problem = o.Check(); !problem.empty()) throw InputError("bench options", problem);
  if (args.cmd == nullptr) return o;
  CheckProtocolFlagsApply(*args.cmd, o.protocol);
  if (!o.slam) {
    for (const char* flag : {"--slam-backend", "--loop-threshold"}) {
      RefuseIfGiven(*args.cmd, flag, "applies to the SLAM back end, which is off; drop it or add --slam");
    }
  }
  if (!UsesFrontEnd(o.methods, {FrontEnd::kKeypoints, FrontEnd::kIdealKeypoints})) {
    RefuseIfGiven(*args.cmd, "--detector", "none of the methods run uses keypoints; add slcd to --methods or drop it");
  }
  return o;
}

void RefuseBenchFlags(const BenchArgs& args, const std::string& why) {
  for (const std::string& flag : args.flags) RefuseIfGiven(*args.cmd, flag, why);
}

void AddGateFlags(CLI::App* cmd, GateArgs* args) {
  CLI::Option* baseline =
      cmd->add_option("--baseline", args->baseline,
                      "earlier report.json: exit 3 when a headline metric (MRR, R@1) of a method in both dropped by "
                      "more than --max-drop");
  cmd->add_option("--max-drop", args->max_drop,
                  "largest allowed drop of MRR or R@1 against --baseline (default 0), or 'ci': a drop is a regression "
                  "only when the baseline's value lies above this run's 95 % interval")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            try {
              DropAllowance::Parse(text, "--max-drop");
            } catch (const InputError&) {
              return std::string("expected a number in [0, 1] or 'ci', got '") + SafeText(text) + "'";
            }
            return "";
          },
          "X|ci"))
      ->needs(baseline);
  cmd->add_option("--junit", args->junit, "write JUnit XML here (one test case per method)");
}

nlohmann::json ReadBaseline(const GateArgs& args, const std::string& mode) {
  if (args.baseline.empty()) return nlohmann::json();
  nlohmann::json baseline = ReadReportJson(args.baseline);
  const auto it = baseline.find("mode");
  const std::string of = it != baseline.end() && it->is_string() ? it->get<std::string>() : "offline";
  if (of != mode) {
    throw InputError(args.baseline, "is the report of an " + of + " bench, this is an " + mode +
                                        " one: --baseline needs a report of the same mode (their figures measure "
                                        "different things)");
  }
  return baseline;
}

int ApplyGate(const GateArgs& args, const nlohmann::json& baseline, const nlohmann::json& report) {
  const DropAllowance allowed = DropAllowance::Parse(args.max_drop, "--max-drop");
  std::vector<Regression> regressions;
  if (!args.baseline.empty()) {
    for (const std::string& m : MethodsOnlyInBaseline(baseline, report)) {
      std::printf("baseline: method %s is not in this run (not compared)\n", m.c_str());
    }
    regressions = CompareToBaseline(baseline, report, allowed);
    for (const Regression& r : regressions) std::printf("%s\n", r.ToString(allowed).c_str());
    if (regressions.empty()) {
      std::printf("baseline %s: no headline metric dropped %s\n", args.baseline.c_str(), allowed.ToString().c_str());
    }
  }
  if (!args.junit.empty()) WriteFileAtomic(args.junit, JUnitXml(report, regressions, allowed));
  return regressions.empty() ? 0 : 3;
}

std::atomic<bool>* CancelOnInterrupt() {
  std::signal(SIGINT, OnInterrupt);
  return &g_interrupted;
}

void PrintWarnings(const std::vector<std::string>& warnings) {
  for (const std::string& warning : warnings) std::fprintf(stderr, "warning: %s\n", warning.c_str());
}

void PrintOutcome(const BenchResult& result, const std::string& report_dir) {
  PrintWarnings(result.skipped);
  // The bench's other figures stand without a true match; its retrieval metrics do not.
  if (!result.no_true_match.empty()) PrintWarnings({result.no_true_match + " ('-' in the table)"});
  std::printf("%s", FormatResultTable(result).c_str());
  std::printf("%s\n", PaperFindingSummary(result).c_str());
  std::printf("report: %s/report.md\n", report_dir.c_str());
}

}  // namespace hoilcd
