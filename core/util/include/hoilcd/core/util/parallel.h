// Parallel loops over index ranges with a fixed thread count, on TBB: one task arena per thread
// count, kept for the life of the process (TBB's workers are started once, not per call). Work
// is split into chunks handed out dynamically; each worker has an id for per-thread scratch
// space. The first exception thrown by any worker is rethrown on the calling thread.
#pragma once

#include <cstdint>
#include <functional>

namespace hoilcd {

// Upper bound of every thread count: larger requests are clamped to it, so no size derived
// from a thread count can overflow.
constexpr int kMaxThreads = 256;

// 0 (or less) means the CPUs this process may use (AvailableCpus, cpus.h); otherwise the number
// asked for; at most kMaxThreads.
int ResolveThreadCount(int requested);

// Calls fn(begin, end, worker) for disjoint chunks [begin, end) covering [0, count).
// worker is in [0, ResolveThreadCount(num_threads)) and no two calls running at the same time
// share one. Chunk boundaries depend only on count and chunk_size, never on timing, so results
// written per index are deterministic.
void ParallelForChunks(int64_t count, int64_t chunk_size, int num_threads,
                       const std::function<void(int64_t, int64_t, int)>& fn);

// Calls fn(i) for every i in [0, count).
void ParallelFor(int64_t count, int num_threads, const std::function<void(int64_t)>& fn);

// Calls fn on the calling thread, in a TBB arena with no worker slots: the parallel loops that
// libraries run in the current TBB arena inside fn (Embree's BVH builds) run there serially. For
// work too small to share: woken workers would spin (sched_yield) long after it ends.
void RunOnCallingThread(const std::function<void()>& fn);

// Process-wide: OpenCV's calls run on the thread that makes them. hoilcd parallelises over frames
// and pairs itself, on the threads asked for; OpenCV keeps a TBB arena of every core of its own,
// which no hoilcd arena reaches, so its calls inside hoilcd's loops ignored the thread count (a
// one-thread bench used 1.04-1.11 cores, a worker spinning). OpenCV replaces that arena without
// a lock, so this is called where a process starts, before any thread uses OpenCV: by the
// hoilcd command line and on import of the Python module (where it applies to the caller's own
// OpenCV calls too).
void KeepOpenCvOnCallingThread();

}  // namespace hoilcd
