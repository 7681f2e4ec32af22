// hoilcd params: every --param NAME of every method and front end, with its unit, default and range.
#include <cstdio>

#include "command.h"
#include "hoilcd/bench/methods/method_params.h"
#include "shared.h"

namespace hoilcd {

Command AddParamsCommand(CLI::App* app) {
  CLI::App* cmd = app->add_subcommand("params", "list the --param NAMEs of every method and front end");
  return {cmd, [] {
            std::printf("%s", FormatParams().c_str());
            return 0;
          }};
}

}  // namespace hoilcd
