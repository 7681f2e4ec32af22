// The hoilcd command line: parses subcommands and flags, runs them, and is the one place
// that turns errors into messages and exit codes.
#pragma once

namespace hoilcd {

// Returns the process exit code: 0 success, 1 bad input or failure, 2 usage error.
int RunCommandLine(int argc, char** argv);

}  // namespace hoilcd
