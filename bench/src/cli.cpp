#include "hoilcd/bench/cli.h"

#include <CLI/CLI.hpp>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <exception>
#include <fstream>
#include <nlohmann/json.hpp>

#include "hoilcd/core/error.h"
#include "hoilcd/core/progress.h"
#include "hoilcd/sim/scene.h"
#include "hoilcd/sim/sequence.h"

namespace hoilcd {
namespace {

std::atomic<bool> g_interrupted{false};

extern "C" void OnInterrupt(int) {
  g_interrupted = true;
  std::signal(SIGINT, SIG_DFL);  // a second Ctrl-C ends the process at once
}

// Flags shared by commands that read a scene.
struct SceneArgs {
  std::string path;
  std::vector<std::string> overrides;
  int64_t seed = -1;
};

Scene LoadSceneArgs(const SceneArgs& args) {
  std::vector<std::string> overrides = args.overrides;
  if (args.seed >= 0) overrides.push_back("seed=" + std::to_string(args.seed));
  return LoadScene(args.path, overrides);
}

int RunValidate(const SceneArgs& args) {
  // Print every problem, not only the first: validation is the point of this command.
  std::ifstream in(args.path);
  if (!in) throw InputError(args.path, "cannot open the scene file (does it exist and is it readable?)");
  const Scene scene = LoadSceneArgs(args);
  std::printf("%s: valid scene '%s' (%d frames at %g Hz, %zu tables, hash %s)\n", args.path.c_str(),
              scene.name.c_str(), scene.frames, scene.frame_rate_hz, scene.tables.size(),
              scene.hash.c_str());
  return 0;
}

int RunRender(const SceneArgs& args, const SequenceOptions& options) {
  const Scene scene = LoadSceneArgs(args);
  std::signal(SIGINT, OnInterrupt);
  SequenceOptions o = options;
  o.cancel = &g_interrupted;
  const SequenceResult r = RenderSequence(scene, o);
  std::printf("rendered %d frames (%d kept from an earlier run) into %s in %.1f s (%.1f frames/s)\n",
              r.frames_rendered, r.frames_reused, o.output_dir.c_str(), r.seconds,
              r.seconds > 0 ? r.frames_rendered / r.seconds : 0.0);
  return 0;
}

void AddSceneFlags(CLI::App* cmd, SceneArgs* args, bool scene_required) {
  auto* opt = cmd->add_option("scene", args->path, "scene file (JSON, see scenes/scene.schema.json)");
  if (scene_required) opt->required();
  cmd->add_option("--set", args->overrides,
                  "override a scene value by its path, e.g. --set crowd.people_per_table=2 (repeatable)")
      ->type_name("KEY=VALUE");
  cmd->add_option("--seed", args->seed, "override the scene's seed")->check(CLI::NonNegativeNumber);
}

}  // namespace

int RunCommandLine(int argc, char** argv) {
  CLI::App app{"hoilcd: synthetic thermal scene simulator and loop-closure benchmark"};
  app.set_version_flag("--version", HOILCD_VERSION);
  app.require_subcommand(1);
  bool quiet = false;
  app.add_flag("-q,--quiet", quiet, "no progress bars");

  SceneArgs validate_args;
  CLI::App* validate = app.add_subcommand("validate", "check a scene file; print every problem with its JSON path");
  AddSceneFlags(validate, &validate_args, true);

  SceneArgs render_args;
  SequenceOptions render_options;
  CLI::App* render = app.add_subcommand("render", "render a scene's sequence into a dataset folder");
  AddSceneFlags(render, &render_args, true);
  render->add_option("-o,--output", render_options.output_dir, "dataset folder (resumed if it holds an interrupted render of the same scene)")
      ->required();
  render->add_option("--frames", render_options.frames, "render only the first N frames (0: all)")
      ->check(CLI::NonNegativeNumber);
  render->add_option("--threads", render_options.threads, "worker threads (0: every core)")
      ->check(CLI::NonNegativeNumber);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  ProgressReporter::SetQuietByDefault(quiet);
  try {
    if (*validate) return RunValidate(validate_args);
    if (*render) return RunRender(render_args, render_options);
  } catch (const InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  } catch (const RenderInterrupted& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 130;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "internal error: %s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace hoilcd
