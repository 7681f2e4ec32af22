// The hoilcd executable: one subcommand per file in apps/hoilcd/ (cli.h parses and dispatches).
#include "cli.h"

int main(int argc, char** argv) { return hoilcd::RunCommandLine(argc, argv); }
