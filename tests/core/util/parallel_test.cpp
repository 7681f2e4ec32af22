#include "hoilcd/core/util/parallel.h"

#include <atomic>
#include <chrono>
#include <climits>
#include <cstdint>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include "hoilcd/core/util/random.h"

namespace hoilcd {
namespace {

TEST(ResolveThreadCount, ZeroMeansEveryCoreAndHugeRequestsAreCapped) {
  EXPECT_GE(ResolveThreadCount(0), 1);
  EXPECT_LE(ResolveThreadCount(0), kMaxThreads);
  EXPECT_EQ(ResolveThreadCount(3), 3);
  EXPECT_EQ(ResolveThreadCount(kMaxThreads + 1), kMaxThreads);
  EXPECT_EQ(ResolveThreadCount(INT_MAX), kMaxThreads);
}

TEST(ParallelForChunks, CoversEveryIndexOnceWithWorkerIdsInRange) {
  for (int threads : {1, 2, 7}) {
    std::vector<std::atomic<int>> hits(1003);
    std::atomic<bool> worker_in_range{true};
    ParallelForChunks(1003, 10, threads, [&](int64_t begin, int64_t end, int worker) {
      if (worker < 0 || worker >= threads) worker_in_range = false;
      for (int64_t i = begin; i < end; ++i) ++hits[i];
    });
    EXPECT_TRUE(worker_in_range) << threads << " threads";
    for (size_t i = 0; i < hits.size(); ++i) ASSERT_EQ(hits[i].load(), 1) << i;
  }
}

TEST(ParallelForChunks, ChunksDependOnlyOnCountAndChunkSize) {
  for (int threads : {1, 3}) {
    std::vector<int64_t> chunk_end(100, -1);
    ParallelForChunks(100, 30, threads, [&](int64_t begin, int64_t end, int) { chunk_end[begin] = end; });
    EXPECT_EQ(chunk_end[0], 30);
    EXPECT_EQ(chunk_end[30], 60);
    EXPECT_EQ(chunk_end[60], 90);
    EXPECT_EQ(chunk_end[90], 100);
  }
}

TEST(ParallelForChunks, HugeThreadCountsAndHugeChunksDoNotOverflow) {
  std::atomic<int64_t> sum{0};
  ParallelForChunks(1000, INT64_MAX, INT_MAX, [&](int64_t begin, int64_t end, int) { sum += end - begin; });
  EXPECT_EQ(sum.load(), 1000);
  sum = 0;
  ParallelFor(1000, INT_MAX, [&](int64_t i) { sum += i; });
  EXPECT_EQ(sum.load(), 999 * 1000 / 2);
}

TEST(ParallelForChunks, PerWorkerScratchGivesTheSameResultAtAnyThreadCount) {
  // Each index is computed in a worker's scratch buffer, as the renderer and the matcher do.
  const auto run = [](int threads) {
    std::vector<double> out(5000);
    std::vector<std::vector<double>> scratch(ResolveThreadCount(threads), std::vector<double>(8));
    ParallelForChunks(5000, 7, threads, [&](int64_t begin, int64_t end, int worker) {
      std::vector<double>& s = scratch[worker];
      for (int64_t i = begin; i < end; ++i) {
        Rng rng = KeyedRng(11, "test.parallel", static_cast<uint64_t>(i));
        for (double& v : s) v = rng.Uniform();
        out[i] = s[0] + s[7];
      }
    });
    return out;
  };
  const std::vector<double> one = run(1);
  EXPECT_EQ(run(2), one);
  EXPECT_EQ(run(8), one);
}

TEST(ParallelForChunks, NestedLoopsNeverShareAWorkersScratch) {
  const int threads = 4;
  std::vector<std::atomic<int>> busy(threads);
  std::atomic<bool> shared{false};
  std::atomic<int64_t> inner_total{0};
  ParallelForChunks(64, 1, threads, [&](int64_t, int64_t, int worker) {
    if (busy[worker]++ != 0) shared = true;
    ParallelFor(50, threads, [&](int64_t i) { inner_total += i; });
    --busy[worker];
  });
  EXPECT_FALSE(shared);
  EXPECT_EQ(inner_total.load(), 64 * (49 * 50 / 2));
}

TEST(ParallelForChunks, AWorkersExceptionReachesTheCaller) {
  for (int threads : {1, 3}) {
    std::atomic<int> calls{0};
    EXPECT_THROW(ParallelForChunks(100, 1, threads,
                                   [&](int64_t begin, int64_t, int) {
                                     ++calls;
                                     if (begin == 42) throw std::runtime_error("chunk 42");
                                   }),
                 std::runtime_error);
    EXPECT_GE(calls.load(), 1);
  }
}

TEST(ParallelFor, EmptyAndNegativeCountsCallNothing) {
  int calls = 0;
  ParallelFor(0, 4, [&](int64_t) { ++calls; });
  ParallelForChunks(-5, 3, 4, [&](int64_t, int64_t, int) { ++calls; });
  EXPECT_EQ(calls, 0);
}

// What Embree's BVH build does inside: a TBB loop in the current arena. Inside
// RunOnCallingThread every iteration runs on the caller, even while our own loops keep workers.
TEST(RunOnCallingThread, ALibrarysTbbLoopInsideRunsOnTheCallingThreadOnly) {
  ParallelFor(64, 2, [](int64_t) {});  // workers exist and are awake
  const std::thread::id caller = std::this_thread::get_id();
  std::mutex mutex;
  std::set<std::thread::id> seen;
  int iterations = 0;
  RunOnCallingThread([&] {
    tbb::parallel_for(0, 2'000, [&](int) {
      std::this_thread::sleep_for(std::chrono::microseconds(20));  // long enough to share
      std::lock_guard<std::mutex> lock(mutex);
      seen.insert(std::this_thread::get_id());
      ++iterations;
    });
  });
  EXPECT_EQ(iterations, 2'000);
  EXPECT_EQ(seen, std::set<std::thread::id>{caller});
}

// --threads 1 means one thread, also for the libraries' loops inside hoilcd's.
TEST(ParallelFor, OneThreadKeepsALibrarysTbbLoopInsideOnTheCallingThread) {
  ParallelFor(64, 2, [](int64_t) {});  // workers exist and are awake
  const std::thread::id caller = std::this_thread::get_id();
  std::mutex mutex;
  std::set<std::thread::id> seen;
  ParallelFor(4, 1, [&](int64_t) {
    tbb::parallel_for(0, 500, [&](int) {
      std::this_thread::sleep_for(std::chrono::microseconds(20));  // long enough to share
      std::lock_guard<std::mutex> lock(mutex);
      seen.insert(std::this_thread::get_id());
    });
  });
  EXPECT_EQ(seen, std::set<std::thread::id>{caller});
}

// Two renders side by side each build their BVHs inside it, at the same time.
TEST(RunOnCallingThread, TwoCallersAtOnceEachRunOnTheirOwnThread) {
  std::mutex mutex;
  std::vector<std::set<std::thread::id>> seen(2);
  std::vector<std::thread::id> callers(2);
  std::atomic<int> inside{0};
  const auto caller = [&](int k) {
    callers[k] = std::this_thread::get_id();
    RunOnCallingThread([&] {
      ++inside;
      while (inside.load() < 2) std::this_thread::yield();  // both are inside at once
      tbb::parallel_for(0, 500, [&](int) {
        std::this_thread::sleep_for(std::chrono::microseconds(20));
        std::lock_guard<std::mutex> lock(mutex);
        seen[k].insert(std::this_thread::get_id());
      });
    });
  };
  std::thread a(caller, 0), b(caller, 1);
  a.join();
  b.join();
  EXPECT_EQ(seen[0], std::set<std::thread::id>{callers[0]});
  EXPECT_EQ(seen[1], std::set<std::thread::id>{callers[1]});
}

TEST(RunOnCallingThread, AnExceptionReachesTheCaller) {
  EXPECT_THROW(RunOnCallingThread([] { throw std::runtime_error("inside"); }), std::runtime_error);
}

}  // namespace
}  // namespace hoilcd
