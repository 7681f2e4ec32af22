#include "hoilcd/core/matching/matching.h"

#include <limits>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "hoilcd/core/util/random.h"
#include "option_properties.h"

namespace hoilcd {
namespace {

// Index of the point of `set` nearest to p by brute force, same float distance, ties to lower index.
int BruteNearest(const std::vector<Point2>& set, Point2 p) {
  int best = -1;
  float best_d = std::numeric_limits<float>::infinity();
  for (int i = 0; i < static_cast<int>(set.size()); ++i) {
    const float dx = set[i].x - p.x, dy = set[i].y - p.y;
    const float d = dx * dx + dy * dy;
    if (d < best_d) {
      best_d = d;
      best = i;
    }
  }
  return best;
}

std::vector<Correspondence> BruteMutual(const std::vector<Point2>& query, const std::vector<Point2>& reference) {
  std::vector<Correspondence> matches;
  for (int i = 0; i < static_cast<int>(query.size()); ++i) {
    const int j = BruteNearest(reference, query[i]);
    if (j >= 0 && BruteNearest(query, reference[j]) == i) matches.push_back({i, j});
  }
  return matches;
}

enum class Layout { kUniform, kClustered, kRow, kIntegerLattice, kFarApart };

std::vector<Point2> MakePoints(Rng& rng, int n, Layout layout) {
  std::vector<Point2> points;
  const float cx = static_cast<float>(rng.Uniform(0, 256)), cy = static_cast<float>(rng.Uniform(0, 192));
  for (int i = 0; i < n; ++i) {
    switch (layout) {
      case Layout::kUniform:
        points.emplace_back(rng.Uniform(0, 256), rng.Uniform(0, 192));
        break;
      case Layout::kClustered:
        points.emplace_back(cx + rng.Normal(0, 3), cy + rng.Normal(0, 3));
        break;
      case Layout::kRow:  // HOI-like: one row of bottom points with small vertical jitter
        points.emplace_back(rng.Uniform(0, 256), 150.0f + static_cast<float>(rng.UniformInt(3)));
        break;
      case Layout::kIntegerLattice:  // many exact distance ties
        points.emplace_back(static_cast<float>(rng.UniformInt(12)), static_cast<float>(rng.UniformInt(9)));
        break;
      case Layout::kFarApart:  // most points far outside the other set's bounding box
        points.emplace_back(rng.Uniform(-2000, 2000), rng.Uniform(-5, 5));
        break;
    }
  }
  return points;
}

TEST(PointGrid, NearestEqualsBruteForceInsideAndOutsideTheCandidateLattice) {
  Rng rng = KeyedRng(2, "test.grid.nearest");
  const Layout layouts[] = {Layout::kUniform, Layout::kClustered, Layout::kRow, Layout::kIntegerLattice,
                            Layout::kFarApart};
  int queries = 0;
  for (int t = 0; t < 200; ++t) {
    const int n = 1 + static_cast<int>(rng.UniformInt(400));
    const std::vector<Point2> set = MakePoints(rng, n, layouts[t % 5]);
    const PointGrid grid(set.data(), n);
    // Random positions around the image, on whole and half pixels (cell borders of integer
    // layouts), at the points themselves and far away.
    std::vector<Point2> probes;
    for (int i = 0; i < 300; ++i) {
      probes.emplace_back(rng.Uniform(-40, 296), rng.Uniform(-40, 232));
      probes.emplace_back(static_cast<float>(rng.UniformInt(26)) * 0.5f - 0.5f,
                          static_cast<float>(rng.UniformInt(20)) * 0.5f - 0.5f);
    }
    for (const Point2& p : set) probes.push_back(p);
    probes.emplace_back(1e4f, -1e4f);
    for (const Point2& p : probes) {
      ASSERT_EQ(grid.Nearest(p), BruteNearest(set, p)) << "problem " << t << " at (" << p.x << ", " << p.y << ")";
      ++queries;
    }
  }
  EXPECT_GT(queries, 100000);
}

TEST(PointGrid, ClusterWithAFarOutlierAndHugeCoordinatesStayExact) {
  Rng rng = KeyedRng(3, "test.grid.outlier");
  // A dense cluster and one far point: most lattice cells lie in the outlier's margin.
  std::vector<Point2> cluster;
  for (int i = 0; i < 3000; ++i) cluster.emplace_back(rng.Uniform(0, 10), rng.Uniform(0, 10));
  cluster.emplace_back(1e5f, 1e5f);
  const PointGrid grid(cluster.data(), static_cast<int>(cluster.size()));
  for (int i = 0; i < 2000; ++i) {
    const Point2 p(static_cast<float>(rng.Uniform(-20, 30)), static_cast<float>(rng.Uniform(-20, 30)));
    ASSERT_EQ(grid.Nearest(p), BruteNearest(cluster, p));
  }
  for (const Point2 p : {Point2(5e4f, 5e4f), Point2(1e5f, 0.0f), Point2(2e5f, 2e5f)}) {
    EXPECT_EQ(grid.Nearest(p), BruteNearest(cluster, p));
  }
  // Finite coordinates whose products overflow float.
  const std::vector<Point2> huge = {{0, 0}, {2e19f, 2e19f}, {-3e18f, 7e18f}};
  const PointGrid huge_grid(huge.data(), static_cast<int>(huge.size()));
  for (const Point2 p : {Point2(1e19f, 1e19f), Point2(0, 1), Point2(-1e18f, 6e18f)}) {
    EXPECT_EQ(huge_grid.Nearest(p), BruteNearest(huge, p));
  }
}

TEST(MutualNearestNeighbours, EqualsBruteForceAndEveryKeptPairIsMutual) {
  Rng rng = KeyedRng(1, "test.mnn");
  const Layout layouts[] = {Layout::kUniform, Layout::kClustered, Layout::kRow, Layout::kIntegerLattice,
                            Layout::kFarApart};
  int total_matches = 0;
  for (int t = 0; t < 400; ++t) {
    const int nq = static_cast<int>(rng.UniformInt(300)), nr = static_cast<int>(rng.UniformInt(300));
    const std::vector<Point2> query = MakePoints(rng, nq, layouts[rng.UniformInt(5)]);
    const std::vector<Point2> reference = MakePoints(rng, nr, layouts[rng.UniformInt(5)]);
    const std::vector<Correspondence> matches = MutualNearestNeighbours(query, reference);
    ASSERT_EQ(matches, BruteMutual(query, reference)) << "problem " << t;
    for (const Correspondence& m : matches) {
      EXPECT_EQ(BruteNearest(reference, query[m.query]), m.reference);
      EXPECT_EQ(BruteNearest(query, reference[m.reference]), m.query);
    }
    total_matches += static_cast<int>(matches.size());
  }
  EXPECT_GT(total_matches, 1000);
}

TEST(MutualNearestNeighbours, TiesGoToTheLowerIndex) {
  // Query 0 is equally far from references 0 and 1; reference 1 is equally far from queries.
  const std::vector<Point2> query = {{0, 0}, {4, 0}, {4, 4}};
  const std::vector<Point2> reference = {{-1, 0}, {1, 0}, {4, 2}};
  const std::vector<Correspondence> expected = {{0, 0}, {1, 2}};
  EXPECT_EQ(MutualNearestNeighbours(query, reference), expected);
  const std::vector<Point2> duplicates = {{5, 5}, {5, 5}, {5, 5}};
  const std::vector<Correspondence> first_only = {{0, 0}};
  EXPECT_EQ(MutualNearestNeighbours(duplicates, duplicates), first_only);
}

TEST(MutualNearestNeighbours, EmptySetsGiveNoMatches) {
  const std::vector<Point2> some = {{1, 2}, {3, 4}};
  EXPECT_TRUE(MutualNearestNeighbours({}, some).empty());
  EXPECT_TRUE(MutualNearestNeighbours(some, {}).empty());
}

TEST(MutualNearestNeighbours, NonFiniteCoordinatesAreRejected) {
  const std::vector<Point2> bad = {{1, 2}, {std::numeric_limits<float>::quiet_NaN(), 4}};
  EXPECT_THROW(MutualNearestNeighbours(bad, bad), std::logic_error);
}

TEST(FilterVertical, DropsExactlyThePairsBeyondTheBound) {
  MatchOptions options;
  options.vertical_tolerance = 0.125;  // 0.125 * 96 = 12 px, exact in binary
  options.image_height_px = 96;
  const std::vector<Point2> query = {{0, 50}, {0, 50}, {0, 50}, {0, 50}, {0, 50}, {0, 50}};
  const std::vector<Point2> reference = {{9, 50}, {0, 62}, {0, 38}, {0, 62.01f}, {0, 37.99f}, {0, 61.99f}};
  const std::vector<Correspondence> matches = {{0, 0}, {1, 1}, {2, 2}, {3, 3}, {4, 4}, {5, 5}};
  const std::vector<Correspondence> expected = {{0, 0}, {1, 1}, {2, 2}, {5, 5}};
  EXPECT_EQ(FilterVertical(query, reference, matches, options), expected);
  options.vertical_tolerance = 0;
  const std::vector<Correspondence> same_row = {{0, 0}};
  EXPECT_EQ(FilterVertical(query, reference, matches, options), same_row);
}

TEST(FilterVertical, OnRandomPairsKeepsThoseWithinAndDropsThoseBeyond) {
  Rng rng = KeyedRng(2, "test.vertical");
  const std::vector<Point2> query = MakePoints(rng, 200, Layout::kUniform);
  const std::vector<Point2> reference = MakePoints(rng, 200, Layout::kUniform);
  std::vector<Correspondence> matches;
  for (int i = 0; i < 200; ++i) matches.push_back({i, static_cast<int>(rng.UniformInt(200))});
  const MatchOptions options;
  const std::vector<Correspondence> kept = FilterVertical(query, reference, matches, options);
  size_t k = 0;
  for (const Correspondence& m : matches) {
    const bool within = std::abs(query[m.query].y - reference[m.reference].y) <= 19.2;
    if (within) {
      ASSERT_LT(k, kept.size());
      EXPECT_EQ(kept[k++], m);
    }
  }
  EXPECT_EQ(k, kept.size());
  EXPECT_LT(kept.size(), matches.size());
}

TEST(MatchOptions, CheckNamesEachInvalidField) {
  EXPECT_EQ(MatchOptions{}.Check(), "");
  MatchOptions bad;
  bad.vertical_tolerance = -0.1;
  bad.image_height_px = 0;
  EXPECT_EQ(bad.Check(), "vertical_tolerance: must be in [0, 1] (got -0.1)");
  EXPECT_THROW(FilterVertical({}, {}, {}, bad), std::logic_error);
  EXPECT_THROW(ScorePair({}, {}, bad, {}, 1, 0, 0), std::logic_error);
  bad.vertical_tolerance = 0.1;
  EXPECT_EQ(bad.Check(), "image_height_px: must be at least 1 px (got 0)");
}

TEST(MatchOptions, HoldsThePapersDefaultsFromItsTableAndChecksEveryBound) {
  EXPECT_EQ(MatchOptions().vertical_tolerance, 0.1);  // paper, section 5.2
  ExpectConstructedHoldsTheTableDefaults<MatchOptions>();
  EXPECT_EQ(ExpectEveryBoundCrossedIsNamedByCheck<MatchOptions>(), 3);
}

TEST(ScorePair, EqualsTheComposedPipelineWithThePairKeyedStream) {
  Rng rng = KeyedRng(3, "test.score");
  EXPECT_EQ(Rng(PairSeed(5, 3, 8)).NextU32(), KeyedRng(5, "ransac", 3, 8).NextU32());
  const MatchOptions match_options;
  const RansacOptions ransac_options;
  for (int t = 0; t < 50; ++t) {
    std::vector<Point2> query = MakePoints(rng, 150, Layout::kUniform);
    std::vector<Point2> reference = query;
    for (Point2& p : reference) {
      p.x += static_cast<float>(3 + rng.Normal(0, 0.7));
      p.y += static_cast<float>(-2 + rng.Normal(0, 0.7));
    }
    reference.resize(100 + rng.UniformInt(50));
    const std::vector<Correspondence> matches =
        FilterVertical(query, reference, MutualNearestNeighbours(query, reference), match_options);
    const int expected =
        EstimateHomographyRansac(query, reference, matches, ransac_options, PairSeed(99, t, t + 1)).inliers;
    EXPECT_EQ(ScorePair(query, reference, match_options, ransac_options, 99, t, t + 1), expected);
  }
}

TEST(MatchPair, ItsInliersAreThePairsScoreAndItsMatchesTheFilteredMutualPairs) {
  Rng rng = KeyedRng(5, "test.match_pair");
  const MatchOptions match_options;
  RansacOptions lo;
  lo.local_optimisation_refits = 2;
  for (const RansacOptions& ransac_options : {RansacOptions(), lo}) {
    for (int t = 0; t < 30; ++t) {
      const std::vector<Point2> query = MakePoints(rng, 20 + t * 4, Layout::kUniform);
      std::vector<Point2> reference = query;
      for (Point2& p : reference)
        p += Point2(static_cast<float>(rng.Normal(2, 1)), static_cast<float>(rng.Normal(0, 1)));
      reference.resize(reference.size() - rng.UniformInt(10));
      const PairMatches pair = MatchPair(query, reference, match_options, ransac_options, 7, t, 2 * t);
      EXPECT_EQ(pair.matches,
                FilterVertical(query, reference, MutualNearestNeighbours(query, reference), match_options));
      ASSERT_EQ(pair.inlier.size(), pair.matches.size());
      int counted = 0;
      for (uint8_t in : pair.inlier) counted += in;
      EXPECT_EQ(counted, pair.inliers);
      EXPECT_EQ(pair.inliers, ScorePair(query, reference, match_options, ransac_options, 7, t, 2 * t));
    }
  }
  const PairMatches few = MatchPair({{1, 1}, {50, 9}}, {{1, 2}, {51, 9}}, match_options, RansacOptions(), 1, 0, 1);
  EXPECT_EQ(few.matches.size(), 2u);
  EXPECT_EQ(few.inliers, 0);
  EXPECT_EQ(few.inlier, std::vector<uint8_t>(2, 0));
}

TEST(ScorePair, ShiftedCopyScoresFarAboveAnUnrelatedFrame) {
  Rng rng = KeyedRng(4, "test.score");
  const std::vector<Point2> query = MakePoints(rng, 200, Layout::kUniform);
  std::vector<Point2> shifted = query;
  for (Point2& p : shifted) p += Point2(2.0f, 1.0f);
  const std::vector<Point2> unrelated = MakePoints(rng, 200, Layout::kUniform);
  const int same = ScorePair(query, shifted, {}, {}, 1, 0, 1);
  const int other = ScorePair(query, unrelated, {}, {}, 1, 0, 2);
  EXPECT_GE(same, 180);  // a few points have a neighbour closer than the 2.2 px shift
  EXPECT_LT(other, same / 2);
}

}  // namespace
}  // namespace hoilcd
