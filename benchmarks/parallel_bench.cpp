// Cost of one parallel loop call (core/util/parallel.h) with almost no work in it: what every row-chunked
// render pass, sensor pass and per-query matching call pays on top of its work.
// Run: build/bin/parallel_bench --benchmark_min_time=0.5
#include <atomic>
#include <cstdint>

#include <benchmark/benchmark.h>

#include "hoilcd/core/util/parallel.h"

namespace {

void BM_ParallelForChunksCall(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  std::atomic<int64_t> sink{0};
  for (auto _ : state) {
    hoilcd::ParallelForChunks(24, 1, threads, [&](int64_t begin, int64_t end, int) {
      sink.fetch_add(end - begin, std::memory_order_relaxed);
    });
  }
  benchmark::DoNotOptimize(sink.load());
}
BENCHMARK(BM_ParallelForChunksCall)->Arg(1)->Arg(2)->Arg(4)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
