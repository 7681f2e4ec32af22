// The hoilcd executable: subcommands render, bench, run, sweep, validate (see bench/cli.h).
#include "hoilcd/bench/cli.h"

int main(int argc, char** argv) { return hoilcd::RunCommandLine(argc, argv); }
