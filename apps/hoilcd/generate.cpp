// hoilcd generate --layout TYPE|mixed|floor --count N --seed S -o DIR: seeded scene files of varied rooms.
#include <chrono>
#include <cstdio>
#include <map>
#include <memory>

#include "command.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/file_io.h"
#include "hoilcd/core/util/folder_lock.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/core/util/progress.h"
#include "hoilcd/core/util/sizes.h"
#include "hoilcd/sim/generate/generator.h"
#include "shared.h"

namespace hoilcd {
namespace {

struct GenerateArgs {
  std::string layout = "mixed";
  int count = 1;
  int start = 0;
  int64_t seed = 1;
  std::string output;
  std::vector<std::string> settings;
  int threads = 0;
};

int GenerateCommand(const GenerateArgs& args) {
  FamilyOf(args.layout, static_cast<uint64_t>(args.seed), args.start);  // a bad --layout fails first
  if (args.start + args.count - 1 > kMaxGeneratedSceneIndex) {
    throw InputError("--start " + std::to_string(args.start) + " --count " + std::to_string(args.count),
                     "scene indices up to " + std::to_string(kMaxGeneratedSceneIndex) + " (the last would be " +
                         std::to_string(args.start + args.count - 1) + ")");
  }
  GeneratorOptions options;
  for (const std::string& setting : args.settings) GeneratorOptions::Table().Set(setting, &options);
  ProblemCollector problems;
  GeneratorOptions::Table().Check(options, "--set", &problems);
  problems.ThrowIfAny();
  CheckGenerateFolder(args.output);
  const FolderLock lock(args.output, FolderLock::IfBusy::kRefuse);  // a second generate into it is refused
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::string> families(static_cast<size_t>(args.count));
  ProgressReporter progress("generate", args.count, "scenes");
  // Each scene draws from its own keyed streams and goes to its own file: any thread order gives
  // the same files.
  ParallelFor(args.count, args.threads, [&](int64_t i) {
    const int index = args.start + static_cast<int>(i);
    const nlohmann::ordered_json scene = GenerateScene(args.layout, static_cast<uint64_t>(args.seed), index, options);
    families[static_cast<size_t>(i)] = scene["generator"]["layout"].get<std::string>();
    WriteFileAtomic(args.output + "/" + GeneratedSceneFileName(index, families[static_cast<size_t>(i)]),
                    SceneFileText(scene));
    progress.Update();
  });
  progress.Done();
  std::map<std::string, int> per_family;
  for (const std::string& f : families) ++per_family[f];
  std::string summary;
  for (const auto& [family, n] : per_family)
    summary += (summary.empty() ? "" : ", ") + std::to_string(n) + " " + family;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("generated %d scene%s (%s) into %s in %.1f s\n", args.count, args.count == 1 ? "" : "s", summary.c_str(),
              args.output.c_str(), seconds);
  return 0;
}

}  // namespace

Command AddGenerateCommand(CLI::App* app) {
  auto args = std::make_shared<GenerateArgs>();
  std::string layouts;
  for (const std::string& f : LayoutFamilies()) layouts += f + ", ";
  CLI::App* cmd = app->add_subcommand("generate", "write seeded scene files of varied rooms (six layout families)");
  cmd->add_option("--layout", args->layout,
                  "layout family: " + layouts +
                      "or mixed (drawn per scene), or floor (a building floor of such rooms along a corridor)")
      ->capture_default_str();
  cmd->add_option("--count", args->count, "scenes to write")
      ->check(NumberIn(OptionRange::Closed(1, kMaxGeneratedSceneIndex)))
      ->capture_default_str();
  cmd->add_option("--start", args->start, "index of the first scene (scene i of a run is the same whatever the count)")
      ->check(NumberIn(OptionRange::Closed(0, kMaxGeneratedSceneIndex)))
      ->capture_default_str();
  cmd->add_option("--seed", args->seed, "seed of the run")
      ->check(NumberIn(OptionRange::Closed(0, static_cast<double>(kMaxSeed))))
      ->capture_default_str();
  cmd->add_option("-o,--output", args->output,
                  "folder of scene files (created when missing; a folder may hold only earlier generated scenes)")
      ->required()
      ->type_name("DIR");
  cmd->add_option(
         "--set", args->settings,
         "a generator option by its name, e.g. --set occupancy_min=0.8 or --set lounge.width_max_m=6 (repeatable; "
         "`hoilcd reference generate` lists them)")
      ->type_name("NAME=VALUE");
  AddThreadsFlag(cmd, &args->threads);
  return {cmd, [args] { return GenerateCommand(*args); }};
}

}  // namespace hoilcd
