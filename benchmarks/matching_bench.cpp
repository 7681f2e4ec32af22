// Mutual nearest neighbours of one frame pair on prebuilt grids (MutualNearestNeighbours), the
// largest single cost of scoring all pairs: frames of 48 points (SLCD's keypoints on paper_room
// average 48 per frame), 38 (its HOI points) and 300 (another detector's keypoints, which take the
// candidate lattice), every pair of a 32 x 32 tile, as the all-pairs loop visits them. Points
// cluster as on real frames (people, furniture edges): each of 8 places has 6 blobs of 8 px
// spread holding 3/4 of its points, the rest uniform. A frame sees its place with a shift of up
// to +-8 px, 1 px jitter and 30 % of the points replaced, so an eighth of the pairs share a place.
// Counters: items_per_second (pairs) and matches_per_pair.
#include <vector>

#include <benchmark/benchmark.h>

#include "hoilcd/core/matching/matching.h"
#include "hoilcd/core/util/random.h"

namespace hoilcd {
namespace {

constexpr int kFrames = 64;
constexpr int kPlaces = 8;
constexpr int kClusters = 6;

struct Frames {
  std::vector<std::vector<Point2>> points;
  std::vector<PointGrid> grids;
};

Frames MakeFrames(int points_per_frame) {
  Frames out;
  std::vector<std::vector<Point2>> places;
  const auto random_point = [](Rng& rng) {
    return Point2(static_cast<float>(rng.Uniform(0, 256)), static_cast<float>(rng.Uniform(0, 192)));
  };
  for (int p = 0; p < kPlaces; ++p) {
    Rng rng = KeyedRng(1, "bench.matching.place", p);
    std::vector<Point2> centres;
    for (int c = 0; c < kClusters; ++c) centres.push_back(random_point(rng));
    places.emplace_back();
    for (int i = 0; i < points_per_frame; ++i) {
      const Point2 c = centres[static_cast<size_t>(rng.UniformInt(kClusters))];
      places.back().push_back(rng.Uniform() < 0.25 ? random_point(rng)
                                                   : Point2(c.x + static_cast<float>(rng.Normal(0, 8)),
                                                            c.y + static_cast<float>(rng.Normal(0, 8))));
    }
  }
  for (int f = 0; f < kFrames; ++f) {
    Rng rng = KeyedRng(1, "bench.matching.frame", f);
    const float shift_x = static_cast<float>(rng.Uniform(-8, 8)), shift_y = static_cast<float>(rng.Uniform(-8, 8));
    std::vector<Point2> frame;
    for (const Point2& p : places[f % kPlaces]) {
      frame.push_back(rng.Uniform() < 0.3 ? random_point(rng)
                                          : Point2(p.x + shift_x + static_cast<float>(rng.Normal(0, 1)),
                                                   p.y + shift_y + static_cast<float>(rng.Normal(0, 1))));
    }
    out.points.push_back(std::move(frame));
  }
  for (const std::vector<Point2>& p : out.points) out.grids.emplace_back(p.data(), static_cast<int>(p.size()));
  return out;
}

void BM_MutualNearestNeighbours(benchmark::State& state) {
  const Frames frames = MakeFrames(static_cast<int>(state.range(0)));
  std::vector<Correspondence> matches;
  int64_t pairs = 0, matched = 0;
  for (auto _ : state) {
    for (int q = 0; q < kFrames / 2; ++q) {
      for (int r = kFrames / 2; r < kFrames; ++r) {
        MutualNearestNeighbours(frames.points[q].data(), frames.grids[q], frames.points[r].data(), frames.grids[r],
                                &matches);
        matched += static_cast<int64_t>(matches.size());
      }
    }
    pairs += (kFrames / 2) * (kFrames / 2);
  }
  state.SetItemsProcessed(pairs);
  state.counters["matches_per_pair"] = static_cast<double>(matched) / static_cast<double>(pairs);
}

BENCHMARK(BM_MutualNearestNeighbours)->Arg(48)->Arg(38)->Arg(300);

}  // namespace
}  // namespace hoilcd

BENCHMARK_MAIN();
