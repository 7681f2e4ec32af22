#include "hoilcd/core/estimators/homography_ransac.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

#include "hoilcd/core/util/random.h"
#include "homography_problems.h"

namespace hoilcd {
namespace {

TEST(EstimateHomographyRansac, FewerThanFourMatchesGiveZeroInliers) {
  Rng rng = KeyedRng(4, "test.ransac");
  for (int n = 0; n < 4; ++n) {
    const HomographyProblem p = MakeHomographyProblem(rng, n, n, 0.0);
    const HomographyResult result = EstimateHomographyRansac(p.query, p.reference, p.matches, {}, 7);
    EXPECT_EQ(result.inliers, 0);
    EXPECT_EQ(result.inlier_mask, std::vector<uint8_t>(n, 0));
    EXPECT_TRUE(result.reference_to_query.isIdentity());
  }
}

TEST(EstimateHomographyRansac, KeepsAtLeast95PercentOfTrueInliersWithHalfOutliersAnd1PxNoise) {
  Rng rng = KeyedRng(5, "test.ransac");
  double found_fraction_sum = 0;
  int problems = 0;
  for (int t = 0; t < 200; ++t) {
    const int n = 50 + static_cast<int>(rng.UniformInt(251));
    const HomographyProblem p = MakeHomographyProblem(rng, n, n / 2, 1.0);
    const HomographyResult result = EstimateHomographyRansac(p.query, p.reference, p.matches, {}, t);
    ASSERT_EQ(static_cast<int>(result.inlier_mask.size()), n);
    EXPECT_EQ(std::accumulate(result.inlier_mask.begin(), result.inlier_mask.end(), 0), result.inliers);
    const int true_found = std::accumulate(result.inlier_mask.begin(), result.inlier_mask.begin() + p.num_inliers, 0);
    found_fraction_sum += static_cast<double>(true_found) / p.num_inliers;
    ++problems;
  }
  // Mean over problems: P(no all-inlier sample in 100 trials at 50 %) is 0.16 %, so an
  // occasional miss is expected and allowed for by averaging.
  EXPECT_GE(found_fraction_sum / problems, 0.95);
}

// Criterion: the same 1000 problems (30-300 matches, 50-90 % inliers, 1 px noise) go to both;
// the total inlier counts must agree within 10 %, and so must the median per-problem relative
// difference. Per-problem counts may differ more when one side's random samples miss the model,
// which is RANSAC's nature, so a per-problem bound would test the random streams, not the code.
TEST(EstimateHomographyRansac, AgreesWithOpenCvRansacOnInlierCounts) {
  Rng rng = KeyedRng(6, "test.ransac");
  double total_ours = 0, total_cv = 0;
  std::vector<double> relative;
  for (int t = 0; t < 1000; ++t) {
    const int n = 30 + static_cast<int>(rng.UniformInt(271));
    const int inliers = static_cast<int>(n * rng.Uniform(0.5, 0.9));
    const HomographyProblem p = MakeHomographyProblem(rng, n, inliers, 1.0);
    const int ours = EstimateHomographyRansac(p.query, p.reference, p.matches, {}, t).inliers;
    std::vector<uint8_t> mask;
    cv::findHomography(p.reference, p.query, cv::RANSAC, 5.0, mask, 100);
    const int theirs = std::accumulate(mask.begin(), mask.end(), 0);
    total_ours += ours;
    total_cv += theirs;
    relative.push_back(std::abs(ours - theirs) / std::max(1.0, static_cast<double>(theirs)));
  }
  std::nth_element(relative.begin(), relative.begin() + relative.size() / 2, relative.end());
  EXPECT_LT(std::abs(total_ours - total_cv) / total_cv, 0.10);
  EXPECT_LT(relative[relative.size() / 2], 0.10);
}

TEST(EstimateHomographyRansac, SameSeedGivesSameResultDifferentSeedsMayDiffer) {
  Rng rng = KeyedRng(7, "test.ransac");
  const HomographyProblem p = MakeHomographyProblem(rng, 120, 40, 1.0);
  const HomographyResult a = EstimateHomographyRansac(p.query, p.reference, p.matches, {}, 11);
  const HomographyResult b = EstimateHomographyRansac(p.query, p.reference, p.matches, {}, 11);
  EXPECT_EQ(a.inliers, b.inliers);
  EXPECT_EQ(a.inlier_mask, b.inlier_mask);
  EXPECT_EQ(a.reference_to_query, b.reference_to_query);
  int differing = 0;
  for (uint64_t seed = 12; seed < 22; ++seed) {
    const HomographyResult c = EstimateHomographyRansac(p.query, p.reference, p.matches, {}, seed);
    differing += c.reference_to_query != a.reference_to_query ? 1 : 0;
  }
  EXPECT_GT(differing, 0);
}

TEST(CountRansacInliers, IsTheEstimatesInlierCountAndRejectsWhatTheEstimateRejects) {
  Rng rng = KeyedRng(9, "test.ransac");
  RansacOptions lo;
  lo.local_optimisation_refits = 2;
  for (int t = 0; t < 30; ++t) {
    const HomographyProblem p = MakeHomographyProblem(rng, 20 + 7 * t, 5 + 3 * t, 1.0);
    for (const RansacOptions& options : {RansacOptions{}, lo}) {
      EXPECT_EQ(CountRansacInliers(p.query, p.reference, p.matches, options, t),
                EstimateHomographyRansac(p.query, p.reference, p.matches, options, t).inliers)
          << t;
    }
  }
  RansacOptions bad;
  bad.trials = 0;
  EXPECT_THROW(CountRansacInliers({}, {}, {}, bad, 1), std::logic_error);
  const std::vector<Point2> points(4, Point2(1, 1));
  EXPECT_THROW(CountRansacInliers(points, points, {{0, 4}}, {}, 1), std::logic_error);
}

// Structure-of-arrays coordinates of a problem's matches, as RansacHomographySoa takes them.
struct SoaMatches {
  std::vector<float> ref_x, ref_y, query_x, query_y;
  explicit SoaMatches(const HomographyProblem& p) {
    for (const Correspondence& m : p.matches) {
      ref_x.push_back(p.reference[m.reference].x);
      ref_y.push_back(p.reference[m.reference].y);
      query_x.push_back(p.query[m.query].x);
      query_y.push_back(p.query[m.query].y);
    }
  }
  int size() const { return static_cast<int>(ref_x.size()); }
};

TEST(RansacCounter, EachVariantCountsWhatItsOwnRansacCountsAndIsChargedItsDrawingAndScoring) {
  // Variants on one stream (plain, LO, other thresholds), on streams of their own (more trials than
  // one chunk of hypotheses, no redrawing, few trials), and a group larger than the eight that
  // share one drawing at once.
  std::vector<RansacOptions> variants(8);
  variants[1].local_optimisation_refits = 2;
  variants[2].inlier_threshold_px = 2.5;
  variants[3].inlier_threshold_px = 2.5, variants[3].local_optimisation_refits = 1;
  variants[4].trials = 300;
  variants[5].trials = 300, variants[5].local_optimisation_refits = 3;
  variants[6].redraw_degenerate_samples = false;
  variants[7].trials = 7;
  std::vector<RansacOptions> crowd(11);
  for (size_t v = 0; v < crowd.size(); ++v) crowd[v].inlier_threshold_px = 1.0 + 0.5 * static_cast<double>(v);
  Rng rng = KeyedRng(10, "test.ransac");
  RansacCounter counter;
  for (int t = 0; t < 40; ++t) {
    const int n = t < 8 ? t : 9 + 6 * t;  // 0..7 matches first: none, too few, exactly 4, a handful
    const HomographyProblem p = MakeHomographyProblem(rng, n, n * (t % 4) / 4, 1.0);
    const SoaMatches m(p);
    for (const std::vector<RansacOptions>* set : {&variants, &crowd}) {
      const int count = static_cast<int>(set->size());
      std::vector<int> inliers(count, -1), untimed(count, -1);
      std::vector<int64_t> alone_ns(count, -1);
      int64_t total_ns = -1;
      counter.Count(m.ref_x.data(), m.ref_y.data(), m.query_x.data(), m.query_y.data(), m.size(), set->data(), count,
                    1000 + t, inliers.data(), alone_ns.data(), &total_ns);
      counter.Count(m.ref_x.data(), m.ref_y.data(), m.query_x.data(), m.query_y.data(), m.size(), set->data(), count,
                    1000 + t, untimed.data(), nullptr, nullptr);
      int64_t sum_ns = 0;
      for (int v = 0; v < count; ++v) {
        const int alone = RansacHomographySoa(m.ref_x.data(), m.ref_y.data(), m.query_x.data(), m.query_y.data(),
                                              m.size(), (*set)[v], 1000 + t, nullptr, nullptr);
        EXPECT_EQ(inliers[v], alone) << "problem " << t << ", variant " << v;
        EXPECT_EQ(untimed[v], alone) << "problem " << t << ", variant " << v;
        EXPECT_GE(alone_ns[v], 0);
        EXPECT_LE(alone_ns[v], total_ns) << "a variant alone costs at most the whole call";
        sum_ns += alone_ns[v];
      }
      // Each stream's drawing is charged to every variant on it: the charges add up to at least
      // the call; below 4 matches nothing runs and nothing is charged.
      EXPECT_GE(sum_ns, total_ns);
      if (n < 4) {
        EXPECT_EQ(total_ns, 0);
        EXPECT_EQ(sum_ns, 0);
      } else {
        EXPECT_GT(total_ns, 0);
        for (int v = 0; v < count; ++v) EXPECT_GT(alone_ns[v], 0) << "variant " << v;
      }
    }
  }
}

TEST(RansacCounter, StopsDrawingOnceEveryMatchIsAnInlierAndNotBefore) {
  std::vector<RansacOptions> variants(2);  // plain and LO on one stream
  variants[1].local_optimisation_refits = 2;
  Rng rng = KeyedRng(11, "test.ransac");
  RansacCounter counter;
  for (int t = 0; t < 20; ++t) {
    const int n = 6 + 3 * t;
    HomographyProblem p = MakeHomographyProblem(rng, n, n, 0.1);  // every match on the homography, to 0.1 px
    for (const bool outlier : {false, true}) {
      if (outlier) p.query.back().x += 40;  // one match far off: n - 1 inliers at best
      const SoaMatches m(p);
      int inliers[2] = {-1, -1};
      counter.Count(m.ref_x.data(), m.ref_y.data(), m.query_x.data(), m.query_y.data(), m.size(), variants.data(), 2,
                    500 + t, inliers, nullptr, nullptr);
      for (int v = 0; v < 2; ++v) {
        EXPECT_EQ(inliers[v], outlier ? n - 1 : n) << "problem " << t << ", variant " << v;
        EXPECT_EQ(inliers[v], RansacHomographySoa(m.ref_x.data(), m.ref_y.data(), m.query_x.data(), m.query_y.data(),
                                                  m.size(), variants[v], 500 + t, nullptr, nullptr));
      }
      if (outlier) {
        EXPECT_EQ(counter.hypotheses_scored(), variants[0].trials)
            << "a search that cannot complete scores every trial";
      } else {
        EXPECT_LT(counter.hypotheses_scored(), variants[0].trials) << "problem " << t;
      }
    }
  }
}

TEST(EstimateHomographyRansac, LocalOptimisationNeverFindsFewerInliersThanPlainWithSameSeed) {
  Rng rng = KeyedRng(8, "test.ransac");
  RansacOptions lo;
  lo.local_optimisation_refits = 2;
  int strictly_more = 0;
  for (int t = 0; t < 100; ++t) {
    const HomographyProblem p = MakeHomographyProblem(rng, 150, 60, 1.5);
    const int plain = EstimateHomographyRansac(p.query, p.reference, p.matches, {}, t).inliers;
    const int refined = EstimateHomographyRansac(p.query, p.reference, p.matches, lo, t).inliers;
    EXPECT_GE(refined, plain);
    strictly_more += refined > plain ? 1 : 0;
  }
  EXPECT_GT(strictly_more, 0);
}

TEST(EstimateHomographyRansac, RedrawingDegenerateSamplesRecoversMoreInliersThanUsingUpTrials) {
  Rng rng = KeyedRng(9, "test.ransac");
  RansacOptions paper_literal;
  paper_literal.redraw_degenerate_samples = false;
  int64_t redrawn = 0, used_up = 0;
  for (int t = 0; t < 100; ++t) {
    const HomographyProblem p = MakeHomographyProblem(rng, 150, 60, 1.0);
    redrawn += EstimateHomographyRansac(p.query, p.reference, p.matches, {}, t).inliers;
    used_up += EstimateHomographyRansac(p.query, p.reference, p.matches, paper_literal, t).inliers;
  }
  EXPECT_GT(redrawn, used_up);
}

TEST(EstimateHomographyRansac, AllCollinearMatchesGiveZeroInliers) {
  std::vector<Point2> line;
  std::vector<Correspondence> matches;
  for (int i = 0; i < 20; ++i) {
    line.emplace_back(10.0f + 5.0f * i, 50.0f);
    matches.push_back({i, i});
  }
  for (bool redraw : {false, true}) {
    RansacOptions options;
    options.redraw_degenerate_samples = redraw;
    EXPECT_EQ(EstimateHomographyRansac(line, line, matches, options, 3).inliers, 0);
  }
}

TEST(RansacOptions, CheckNamesEachInvalidFieldAndEstimateRejectsThem) {
  EXPECT_EQ(RansacOptions{}.Check(), "");
  RansacOptions bad;
  bad.trials = 0;
  bad.inlier_threshold_px = -1;
  bad.local_optimisation_refits = -2;
  EXPECT_EQ(bad.Check(), "trials: must be in [1, 10000000] (got 0)");
  EXPECT_THROW(EstimateHomographyRansac({}, {}, {}, bad, 1), std::logic_error);
  bad.trials = 100;
  EXPECT_EQ(bad.Check(), "inlier_threshold_px: must be above 0 px (got -1)");
  bad.inlier_threshold_px = 5;
  EXPECT_EQ(bad.Check(), "local_optimisation_refits: must be in [0, 100] (got -2)");
  RansacOptions too_many;
  too_many.trials = 20'000'000;  // sample counters would pass 2^32
  EXPECT_EQ(too_many.Check(), "trials: must be in [1, 10000000] (got 20000000)");
}

TEST(EstimateHomographyRansac, OutOfRangeMatchIsRejected) {
  const std::vector<Point2> points(4, Point2(1, 1));
  EXPECT_THROW(EstimateHomographyRansac(points, points, {{0, 4}}, {}, 1), std::logic_error);
}

}  // namespace
}  // namespace hoilcd
