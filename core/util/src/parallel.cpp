#include "hoilcd/core/util/parallel.h"

#include <algorithm>
#include <map>
#include <memory>
#include <mutex>

#include <opencv2/core/utility.hpp>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include "hoilcd/core/util/cpus.h"

namespace hoilcd {
namespace {

// The arena of `threads` slots, created on first use and kept: an arena costs a few
// microseconds to set up, and a render makes thousands of parallel calls.
tbb::task_arena& ArenaFor(int threads) {
  // TBB starts at most one worker per core unless allowed more; --threads above the core count
  // gets its threads, as it did before TBB.
  static const tbb::global_control allow_threads(tbb::global_control::max_allowed_parallelism, kMaxThreads);
  static std::mutex mutex;
  static std::map<int, std::unique_ptr<tbb::task_arena>> arenas;
  std::lock_guard<std::mutex> lock(mutex);
  std::unique_ptr<tbb::task_arena>& arena = arenas[threads];
  if (!arena) {
    arena = std::make_unique<tbb::task_arena>(threads);
    arena->initialize();
  }
  return *arena;
}

}  // namespace

int ResolveThreadCount(int requested) {
  if (requested > 0) return std::min(requested, kMaxThreads);
  // Read once: the affinity and quota of a run do not change while it runs.
  static const int available = AvailableCpus();
  return std::min(available, kMaxThreads);
}

void ParallelForChunks(int64_t count, int64_t chunk_size, int num_threads,
                       const std::function<void(int64_t, int64_t, int)>& fn) {
  if (count <= 0) return;
  chunk_size = std::max<int64_t>(1, chunk_size);
  const int64_t num_chunks = count / chunk_size + (count % chunk_size != 0 ? 1 : 0);
  const int threads = static_cast<int>(std::min<int64_t>(ResolveThreadCount(num_threads), num_chunks));
  const auto run_chunk = [&](int64_t chunk, int worker) {
    const int64_t begin = chunk * chunk_size;
    fn(begin, begin + std::min(chunk_size, count - begin), worker);
  };
  if (threads <= 1) {
    // In a one-slot arena, so that TBB loops inside fn (a library's, run in the current arena)
    // stay on this thread too: in TBB's default arena they would wake a worker per core, which
    // then spins. (OpenCV's keep an arena of their own: KeepOpenCvOnCallingThread.)
    RunOnCallingThread([&] {
      for (int64_t chunk = 0; chunk < num_chunks; ++chunk) run_chunk(chunk, 0);
    });
    return;
  }
  ArenaFor(threads).execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<int64_t>(0, num_chunks, 1),
        [&](const tbb::blocked_range<int64_t>& range) {
          const int worker = tbb::this_task_arena::current_thread_index();
          // Isolated: a nested parallel loop inside fn must not make this thread pick up
          // another chunk of this loop, which would share the worker's scratch space.
          tbb::this_task_arena::isolate([&] {
            for (int64_t chunk = range.begin(); chunk < range.end(); ++chunk) {
              run_chunk(chunk, worker);
            }
          });
        },
        tbb::simple_partitioner());
  });
}

void ParallelFor(int64_t count, int num_threads, const std::function<void(int64_t)>& fn) {
  const int threads = ResolveThreadCount(num_threads);
  const int64_t chunk = std::max<int64_t>(1, count / (threads * 16));
  ParallelForChunks(count, chunk, threads, [&](int64_t begin, int64_t end, int) {
    for (int64_t i = begin; i < end; ++i) fn(i);
  });
}

void RunOnCallingThread(const std::function<void()>& fn) { ArenaFor(1).execute(fn); }

void KeepOpenCvOnCallingThread() { cv::setNumThreads(0); }

}  // namespace hoilcd
