// The hoilcd executable: subcommands render, bench, run, sweep, validate (see bench/cli.h).
#include "hoilcd/bench/cli.h"
#include "hoilcd/core/allocator.h"

int main(int argc, char** argv) {
  hoilcd::KeepFreedMemoryForReuse();  // every subcommand reads or writes frame after frame
  return hoilcd::RunCommandLine(argc, argv);
}
