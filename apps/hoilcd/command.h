// One subcommand of the hoilcd command line: each file in apps/hoilcd/ adds one to the CLI11 app
// (its flags, help and the function that runs it once the command line is parsed).
#pragma once

#include <functional>

namespace CLI {
class App;
}

namespace hoilcd {

struct Command {
  CLI::App* app = nullptr;   // the parsed subcommand; *app is true when the user chose it
  std::function<int()> run;  // the exit code: 0 success, 3 a CI gate regression
};

Command AddValidateCommand(CLI::App* app);
Command AddRenderCommand(CLI::App* app);
Command AddMergeCommand(CLI::App* app);
Command AddBenchCommand(CLI::App* app);
Command AddRunCommand(CLI::App* app);
Command AddEvaluateCommand(CLI::App* app);
Command AddInspectCommand(CLI::App* app);
Command AddRealismCommand(CLI::App* app);
Command AddSweepCommand(CLI::App* app);
Command AddExportMotCommand(CLI::App* app);
Command AddExportCocoCommand(CLI::App* app);
Command AddExportMcapCommand(CLI::App* app);
Command AddParamsCommand(CLI::App* app);
Command AddReferenceCommand(CLI::App* app);
Command AddGenerateCommand(CLI::App* app);
Command AddSuiteCommand(CLI::App* app);

}  // namespace hoilcd
