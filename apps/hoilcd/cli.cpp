#include "cli.h"

#include <cstdio>
#include <exception>
#include <vector>

#include <CLI/CLI.hpp>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/core/util/progress.h"
#include "hoilcd/sim/output/sequence.h"

namespace hoilcd {

std::vector<Command> AddCommands(CLI::App* app, bool* quiet) {
  app->set_version_flag("--version", HOILCD_VERSION);
  app->require_subcommand(1);
  app->add_flag("-q,--quiet", *quiet, "no progress bars");
  return {AddValidateCommand(app),   AddRenderCommand(app),   AddMergeCommand(app),     AddBenchCommand(app),
          AddRunCommand(app),        AddEvaluateCommand(app), AddInspectCommand(app),   AddSweepCommand(app),
          AddExportCocoCommand(app), AddParamsCommand(app),   AddExportMotCommand(app), AddReferenceCommand(app),
          AddGenerateCommand(app),   AddSuiteCommand(app),    AddRealismCommand(app),   AddExportMcapCommand(app)};
}

int RunCommandLine(int argc, char** argv) {
  KeepOpenCvOnCallingThread();  // every command's loops run on its --threads
  CLI::App app{"hoilcd: synthetic thermal scene simulator and loop-closure benchmark"};
  bool quiet = false;
  const std::vector<Command> commands = AddCommands(&app, &quiet);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  ProgressReporter::SetQuietByDefault(quiet);
  try {
    for (const Command& command : commands) {
      if (*command.app) return command.run();
    }
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
