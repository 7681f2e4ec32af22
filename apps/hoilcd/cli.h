// The hoilcd command line: parses subcommands and flags, runs them, and is the one place
// that turns errors into messages and exit codes.
#pragma once

#include <vector>

#include "command.h"

namespace hoilcd {

// Adds the global flags (-q into *quiet, --version) and every subcommand to `app`: what
// RunCommandLine parses, and where tests find every flag of every command.
std::vector<Command> AddCommands(CLI::App* app, bool* quiet);

// Returns the process exit code: 0 success, 1 bad input or failure, 2 usage error.
int RunCommandLine(int argc, char** argv);

}  // namespace hoilcd
