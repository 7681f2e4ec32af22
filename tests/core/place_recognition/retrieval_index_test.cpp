#include "hoilcd/core/place_recognition/retrieval_index.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "hoilcd/core/util/random.h"

namespace hoilcd {
namespace {

// Frames in small groups that see the same points shifted and jittered, so scores vary from 0
// to nearly all points; a few frames are tiny (0, 3 or 5 points).
std::vector<std::vector<Point2>> MakeFrames(int count) {
  Rng rng = KeyedRng(1, "test.index");
  std::vector<std::vector<Point2>> frames;
  std::vector<Point2> base;
  for (int f = 0; f < count; ++f) {
    if (f % 4 == 0) {
      base.clear();
      for (int i = 0; i < 120; ++i) base.emplace_back(rng.Uniform(0, 256), rng.Uniform(0, 192));
    }
    std::vector<Point2> frame;
    const float shift_x = static_cast<float>(rng.Uniform(-6, 6));
    for (const Point2& p : base) {
      if (rng.Uniform() < 0.2) continue;
      frame.emplace_back(p.x + shift_x + static_cast<float>(rng.Normal(0, 0.8)),
                         p.y + static_cast<float>(rng.Normal(0, 0.8)));
    }
    const int tiny[] = {0, 3, 5};
    if (f % 7 == 6) frame.resize(tiny[f % 3]);
    frames.push_back(frame);
  }
  return frames;
}

TEST(RetrievalIndex, StoresEachFramesPointsInAddOrder) {
  const std::vector<std::vector<Point2>> frames = MakeFrames(9);
  RetrievalIndex index;
  for (const auto& frame : frames) index.Add(frame);
  ASSERT_EQ(index.size(), 9);
  for (int f = 0; f < 9; ++f) {
    int count = -1;
    const Point2* points = index.points(f, &count);
    ASSERT_EQ(count, static_cast<int>(frames[f].size()));
    for (int i = 0; i < count; ++i) EXPECT_EQ(points[i], frames[f][i]);
  }
  int count = 0;
  EXPECT_THROW(index.points(9, &count), std::logic_error);
}

TEST(RetrievalIndex, AddingFramesTogetherInParallelGivesTheIndexOfAddingThemOneByOne) {
  const std::vector<std::vector<Point2>> frames = MakeFrames(23);
  RetrievalIndex one_by_one;
  for (const std::vector<Point2>& f : frames) one_by_one.Add(f);
  std::vector<int> all(frames.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  const auto expected = one_by_one.ScoreAll(all, all, MatchOptions(), RansacOptions(), 7, 1);
  for (int threads : {1, 2, 3}) {
    RetrievalIndex together;
    together.Add(frames[0]);  // appended after frames already there, in two calls
    together.AddAll(std::vector<std::vector<Point2>>(frames.begin() + 1, frames.begin() + 10), threads);
    together.AddAll(std::vector<std::vector<Point2>>(frames.begin() + 10, frames.end()), threads);
    ASSERT_EQ(together.size(), one_by_one.size());
    for (int f = 0; f < together.size(); ++f) {
      int a = 0, b = 0;
      const Point2* pa = together.points(f, &a);
      const Point2* pb = one_by_one.points(f, &b);
      ASSERT_EQ(a, b) << f;
      for (int i = 0; i < a; ++i) EXPECT_EQ(pa[i], pb[i]) << f;
    }
    EXPECT_EQ(together.ScoreAll(all, all, MatchOptions(), RansacOptions(), 7, 1), expected) << threads;
  }
}

TEST(RetrievalIndex, ScoreAllEqualsScorePairPerPairAndIsIdenticalAtOneAndTwoThreads) {
  // 40 queries x 70 references: more than one 32 x 32 tile each way, with partial tiles, so
  // both threads get work and tile edges are crossed.
  const std::vector<std::vector<Point2>> frames = MakeFrames(70);
  RetrievalIndex index;
  for (const auto& frame : frames) index.Add(frame);
  std::vector<int> queries;
  for (int i = 0; i < 40; ++i) queries.push_back((i * 37 + 13) % 70);
  std::vector<int> database;
  for (int f = 0; f < 70; f += 1) database.push_back(f);
  const MatchOptions match_options;
  RansacOptions ransac_options;
  ransac_options.local_optimisation_refits = 1;
  const auto one = index.ScoreAll(queries, database, match_options, ransac_options, 77, 1);
  const auto two = index.ScoreAll(queries, database, match_options, ransac_options, 77, 2);
  EXPECT_EQ(one, two);
  ASSERT_EQ(one.size(), queries.size());
  float best = 0;
  for (size_t i = 0; i < queries.size(); ++i) {
    ASSERT_EQ(one[i].size(), database.size());
    for (size_t j = 0; j < database.size(); ++j) {
      const int expected = ScorePair(frames[queries[i]], frames[database[j]], match_options, ransac_options, 77,
                                     queries[i], database[j]);
      EXPECT_EQ(one[i][j], static_cast<float>(expected)) << queries[i] << " vs " << database[j];
      best = std::max(best, one[i][j]);
    }
  }
  EXPECT_GT(best, 50.0f);  // related frames do score
}

TEST(RetrievalIndex, ScoreAllRejectsUnknownFramesAndBadOptions) {
  RetrievalIndex index;
  index.Add({{1, 1}, {2, 2}});
  EXPECT_THROW(index.ScoreAll({0}, {1}, {}, {}, 1, 1), std::logic_error);
  RansacOptions bad;
  bad.trials = 0;
  EXPECT_THROW(index.ScoreAll({0}, {0}, {}, bad, 1, 1), std::logic_error);
  EXPECT_TRUE(index.ScoreAll({}, {0}, {}, {}, 1, 1).empty());
}

TEST(RetrievalIndex, ScoreDatabasesEqualsScoreAllPerQueryAtAnyThreadCount) {
  // 70 frames: queries 40..69, each against its own ascending database (the frames before it
  // minus a window, in steps that differ per query), crossing 32-frame tile edges.
  const std::vector<std::vector<Point2>> frames = MakeFrames(70);
  RetrievalIndex index;
  for (const auto& frame : frames) index.Add(frame);
  std::vector<int> queries;
  std::vector<std::vector<int>> databases;
  for (int q = 40; q < 70; ++q) {
    queries.push_back(q);
    databases.emplace_back();
    for (int r = q % 3; r < q - 5; r += 1 + q % 2) databases.back().push_back(r);
  }
  databases[3].clear();  // an empty database scores nothing
  const MatchOptions match;
  const RansacOptions ransac;
  std::vector<int64_t> time_ns;
  ProgressReporter progress("test", 0, "pairs", /*quiet=*/true);
  const auto one = index.ScoreDatabases(queries, databases, match, ransac, 9, 1, &time_ns, &progress);
  ASSERT_EQ(one.size(), queries.size());
  ASSERT_EQ(time_ns.size(), queries.size());
  bool some_score = false;
  for (size_t i = 0; i < queries.size(); ++i) {
    const auto expected = databases[i].empty() ? std::vector<std::vector<float>>{{}}
                                               : index.ScoreAll({queries[i]}, databases[i], match, ransac, 9, 1);
    EXPECT_EQ(one[i], expected[0]) << "query " << queries[i];
    EXPECT_GE(time_ns[i], 0);
    for (float v : one[i]) some_score |= v > 0;
  }
  EXPECT_TRUE(some_score);
  for (int threads : {2, 3}) {
    EXPECT_EQ(index.ScoreDatabases(queries, databases, match, ransac, 9, threads), one) << threads << " threads";
  }
}

TEST(RetrievalIndex, ScoringUnderSeveralRansacVariantsInOnePassGivesEachVariantsOwnScores) {
  const std::vector<std::vector<Point2>> frames = MakeFrames(70);
  RetrievalIndex index;
  index.AddAll(frames, 2);
  std::vector<int> queries;
  std::vector<std::vector<int>> databases;
  for (int q = 36; q < 70; q += 2) {
    queries.push_back(q);
    databases.emplace_back();
    for (int r = q % 4; r < q - 3; ++r) databases.back().push_back(r);
  }
  const MatchOptions match;
  RansacOptions lo, few, strict;
  lo.local_optimisation_refits = 2;
  few.trials = 7;
  strict.inlier_threshold_px = 1.0;
  const std::vector<RansacOptions> variants = {RansacOptions(), lo, few, strict};
  std::vector<std::vector<int64_t>> time_ns;
  ProgressReporter progress("test", 0, "pairs", /*quiet=*/true);
  const auto tables = index.ScoreDatabases(queries, databases, match, variants, 5, 2, &time_ns, &progress);
  ASSERT_EQ(tables.size(), variants.size());
  ASSERT_EQ(time_ns.size(), variants.size());
  for (size_t v = 0; v < variants.size(); ++v) {
    EXPECT_EQ(tables[v], index.ScoreDatabases(queries, databases, match, variants[v], 5, 1)) << "variant " << v;
    ASSERT_EQ(time_ns[v].size(), queries.size());
    for (int64_t ns : time_ns[v]) EXPECT_GT(ns, 0);  // every database has pairs
  }
  EXPECT_NE(tables[0], tables[2]);  // the variants differ, so the check above can tell them apart
  EXPECT_NE(tables[0], tables[3]);
  for (int threads : {1, 3}) {
    EXPECT_EQ(index.ScoreDatabases(queries, databases, match, variants, 5, threads), tables) << threads << " threads";
  }
  EXPECT_THROW(index.ScoreDatabases(queries, databases, match, std::vector<RansacOptions>{}, 5, 1), std::logic_error);
}

TEST(RetrievalIndex, ScoreDatabasesRejectsADatabaseThatIsNotAscendingOrAMissingOne) {
  const std::vector<std::vector<Point2>> frames = MakeFrames(8);
  RetrievalIndex index;
  for (const auto& frame : frames) index.Add(frame);
  EXPECT_THROW(index.ScoreDatabases({7}, {{1, 0}}, MatchOptions{}, RansacOptions{}, 1, 1), std::logic_error);
  EXPECT_THROW(index.ScoreDatabases({7}, {{0, 8}}, MatchOptions{}, RansacOptions{}, 1, 1), std::logic_error);
  EXPECT_THROW(index.ScoreDatabases({7, 6}, {{0}}, MatchOptions{}, RansacOptions{}, 1, 1), std::logic_error);
}

}  // namespace
}  // namespace hoilcd
