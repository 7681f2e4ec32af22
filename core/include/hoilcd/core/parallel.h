// Parallel loops over index ranges with a fixed thread count. Work is split into chunks handed
// out dynamically; each worker has an id for per-thread scratch space. The first exception
// thrown by any worker is rethrown on the calling thread after all workers stop.
#pragma once

#include <cstdint>
#include <functional>

namespace hoilcd {

// 0 means "every core"; otherwise the number asked for (at least 1).
int ResolveThreadCount(int requested);

// Calls fn(begin, end, worker) for disjoint chunks [begin, end) covering [0, count).
// worker is in [0, num_threads). Chunk boundaries depend only on count and chunk_size,
// never on timing, so results written per index are deterministic.
void ParallelForChunks(int64_t count, int64_t chunk_size, int num_threads,
                       const std::function<void(int64_t, int64_t, int)>& fn);

// Calls fn(i) for every i in [0, count).
void ParallelFor(int64_t count, int num_threads, const std::function<void(int64_t)>& fn);

}  // namespace hoilcd
