// Must not compile: the measuring code reads datasets, never the simulator (tests/layout).
#include "hoilcd/bench/report/report.h"
#include "hoilcd/bench/runner/runner.h"
#include "hoilcd/sim/output/sequence.h"
