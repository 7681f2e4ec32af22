// All-pairs scoring through RetrievalIndex::ScoreAll: 1000 query x 1000 database frames of 200
// points each (MNN -> vertical filter -> 100-hypothesis RANSAC per pair) on 2 threads; the
// target is <= 10 s for the million pairs. Frames come from 100 places, each a fixed set of 200
// points seen by 20 frames with a shift of up to +-8 px, 1 px jitter and 30 % of the points
// replaced, so a tenth of the pairs are true revisits with many inliers and the rest score low.
// Counters: pairs_per_s (wall clock), cpu_us_per_pair (process CPU time over all threads, which
// a busy shared machine inflates less than wall time) and mean_score (inliers per pair).
#include <ctime>
#include <vector>

#include <benchmark/benchmark.h>

#include "hoilcd/core/place_recognition/retrieval_index.h"
#include "hoilcd/core/util/random.h"

namespace hoilcd {
namespace {

constexpr int kFramesPerSide = 1000;
constexpr int kPointsPerFrame = 200;
constexpr int kPlaces = 100;

std::vector<Point2> RandomPoints(Rng& rng, int n) {
  std::vector<Point2> points;
  for (int i = 0; i < n; ++i) {
    points.emplace_back(static_cast<float>(rng.Uniform(0, 256)), static_cast<float>(rng.Uniform(0, 192)));
  }
  return points;
}

// Frames 0..999 are the database, 1000..1999 the queries; frame f views place f % kPlaces.
RetrievalIndex BuildIndex() {
  std::vector<std::vector<Point2>> places;
  for (int p = 0; p < kPlaces; ++p) {
    Rng rng = KeyedRng(1, "bench.all_pairs.place", p);
    places.push_back(RandomPoints(rng, kPointsPerFrame));
  }
  RetrievalIndex index;
  for (int f = 0; f < 2 * kFramesPerSide; ++f) {
    Rng rng = KeyedRng(1, "bench.all_pairs.frame", f);
    const float shift_x = static_cast<float>(rng.Uniform(-8, 8));
    const float shift_y = static_cast<float>(rng.Uniform(-8, 8));
    std::vector<Point2> frame;
    for (const Point2& p : places[f % kPlaces]) {
      if (rng.Uniform() < 0.3) {
        frame.emplace_back(static_cast<float>(rng.Uniform(0, 256)), static_cast<float>(rng.Uniform(0, 192)));
      } else {
        frame.emplace_back(p.x + shift_x + static_cast<float>(rng.Normal(0, 1)),
                           p.y + shift_y + static_cast<float>(rng.Normal(0, 1)));
      }
    }
    index.Add(frame);
  }
  return index;
}

void BM_AllPairs(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  const RetrievalIndex index = BuildIndex();
  std::vector<int> database, queries;
  for (int f = 0; f < kFramesPerSide; ++f) {
    database.push_back(f);
    queries.push_back(kFramesPerSide + f);
  }
  double score_sum = 0;
  const std::clock_t cpu_start = std::clock();
  for (auto _ : state) {
    const std::vector<std::vector<float>> scores =
        index.ScoreAll(queries, database, MatchOptions{}, RansacOptions{}, 7, threads);
    score_sum = 0;
    for (const auto& row : scores) {
      for (float s : row) score_sum += s;
    }
  }
  const double cpu_s = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  const double pairs = static_cast<double>(queries.size()) * database.size();
  state.counters["cpu_us_per_pair"] = cpu_s * 1e6 / (pairs * state.iterations());
  state.counters["pairs_per_s"] = benchmark::Counter(pairs * state.iterations(), benchmark::Counter::kIsRate);
  state.counters["mean_score"] = score_sum / pairs;
}

BENCHMARK(BM_AllPairs)->Arg(2)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace
}  // namespace hoilcd

BENCHMARK_MAIN();
