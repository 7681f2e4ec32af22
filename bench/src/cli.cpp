#include "hoilcd/bench/cli.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "hoilcd/core/error.h"

namespace hoilcd {

int RunCommandLine(int argc, char** argv) {
  CLI::App app{"hoilcd: synthetic thermal scene simulator and loop-closure benchmark"};
  app.set_version_flag("--version", HOILCD_VERSION);
  app.require_subcommand(1);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
  } catch (const InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "internal error: %s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace hoilcd
