// The apps tests' way to run the command line in-process: `hoilcd -q ARGS...` with its exit code and
// what it printed to stdout and stderr.
#pragma once

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cli.h"

namespace hoilcd::test {

struct CliOutcome {
  int exit_code = 0;
  std::string out, err;
};

inline CliOutcome RunCli(std::vector<std::string> args) {
  args.insert(args.begin(), {"hoilcd", "-q"});
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  const int code = RunCommandLine(static_cast<int>(argv.size()), argv.data());
  const std::string out = testing::internal::GetCapturedStdout();
  return {code, out, testing::internal::GetCapturedStderr()};
}

}  // namespace hoilcd::test
