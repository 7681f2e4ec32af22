// Benchmarks the example's column-profile method beside hoilcd's SLCD on a dataset folder:
//   column_profile_bench DATASET [REPORT_DIR]
// Registering the method is the one line that makes hoilcd know it; the runner, the metrics and
// the report then treat it like a built-in.
#include <cstdio>
#include <exception>

#include "column_profile_method.h"
#include "hoilcd/bench/methods/methods.h"
#include "hoilcd/bench/report/report.h"
#include "hoilcd/bench/runner/runner.h"
#include "hoilcd/core/util/error.h"

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: %s DATASET [REPORT_DIR]\n", argv[0]);
    return 2;
  }
  try {
    hoilcd::RegisterMethod(MakeColumnProfileMethod);
    const hoilcd::Dataset dataset = hoilcd::Dataset::Open(argv[1]);
    hoilcd::BenchOptions options;
    options.methods = hoilcd::ParseMethodList("column-profile,slcd");
    const hoilcd::BenchResult result = hoilcd::RunBench(dataset, options);
    for (const hoilcd::MethodRun& run : result.runs) {
      std::printf("%s: MRR %.4f, R@1 %.4f over %d queries\n", run.name.c_str(), run.metrics.mrr,
                  run.metrics.recall_at_1, run.metrics.queries_scored);
    }
    if (argc == 3) {
      hoilcd::ReportTiming timing;
      timing.bench_s = result.seconds;
      hoilcd::WriteReport(result, dataset, options, timing, argv[2]);
      std::printf("report: %s/report.md\n", argv[2]);
    }
  } catch (const hoilcd::InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "internal error: %s\n", e.what());
    return 1;
  }
  return 0;
}
