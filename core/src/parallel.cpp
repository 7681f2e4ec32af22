#include "hoilcd/core/parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace hoilcd {

int ResolveThreadCount(int requested) {
  if (requested > 0) return requested;
  const unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : static_cast<int>(hw);
}

void ParallelForChunks(int64_t count, int64_t chunk_size, int num_threads,
                       const std::function<void(int64_t, int64_t, int)>& fn) {
  if (count <= 0) return;
  chunk_size = std::max<int64_t>(1, chunk_size);
  const int64_t num_chunks = (count + chunk_size - 1) / chunk_size;
  const int threads = static_cast<int>(
      std::min<int64_t>(ResolveThreadCount(num_threads), num_chunks));
  std::atomic<int64_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto worker = [&](int id) {
    for (;;) {
      if (failed.load(std::memory_order_relaxed)) return;
      const int64_t chunk = next.fetch_add(1);
      if (chunk >= num_chunks) return;
      const int64_t begin = chunk * chunk_size;
      try {
        fn(begin, std::min(count, begin + chunk_size), id);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        failed = true;
        return;
      }
    }
  };
  if (threads <= 1) {
    worker(0);
  } else {
    std::vector<std::thread> pool;
    pool.reserve(threads - 1);
    for (int t = 1; t < threads; ++t) pool.emplace_back(worker, t);
    worker(0);
    for (std::thread& t : pool) t.join();
  }
  if (error) std::rethrow_exception(error);
}

void ParallelFor(int64_t count, int num_threads, const std::function<void(int64_t)>& fn) {
  const int threads = ResolveThreadCount(num_threads);
  const int64_t chunk = std::max<int64_t>(1, count / (threads * 16));
  ParallelForChunks(count, chunk, threads, [&](int64_t begin, int64_t end, int) {
    for (int64_t i = begin; i < end; ++i) fn(i);
  });
}

}  // namespace hoilcd
