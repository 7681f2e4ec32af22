#include "hoilcd/core/estimators/homography_ransac.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <vector>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "hoilcd/core/util/random.h"
#include "option_properties.h"

namespace hoilcd {
namespace {

constexpr float kWidthPx = 256, kHeightPx = 192;

// A plausible reference -> query homography: scale/shear near 1, shift, mild perspective.
Eigen::Matrix3d RandomHomography(Rng& rng) {
  Eigen::Matrix3d h;
  h << rng.Uniform(0.8, 1.2), rng.Uniform(-0.15, 0.15), rng.Uniform(-25, 25),
      rng.Uniform(-0.15, 0.15), rng.Uniform(0.8, 1.2), rng.Uniform(-20, 20),
      rng.Uniform(-6e-4, 6e-4), rng.Uniform(-6e-4, 6e-4), 1.0;
  return h;
}

Point2 Apply(const Eigen::Matrix3d& h, Point2 p) {
  const Eigen::Vector3d q = h * Eigen::Vector3d(p.x, p.y, 1.0);
  return Point2(static_cast<float>(q.x() / q.z()), static_cast<float>(q.y() / q.z()));
}

Point2 RandomPoint(Rng& rng) {
  return Point2(static_cast<float>(rng.Uniform(0, kWidthPx)),
                static_cast<float>(rng.Uniform(0, kHeightPx)));
}

// Matches 0..n-1 pair reference[i] with query[i]; the first `num_inliers` follow h plus Gaussian
// noise of noise_px per axis, the rest are uniform outliers.
struct Problem {
  std::vector<Point2> query, reference;
  std::vector<Correspondence> matches;
  int num_inliers = 0;
};

Problem MakeProblem(Rng& rng, int n, int num_inliers, double noise_px) {
  Problem p;
  const Eigen::Matrix3d h = RandomHomography(rng);
  p.num_inliers = num_inliers;
  for (int i = 0; i < n; ++i) {
    const Point2 r = RandomPoint(rng);
    Point2 q = RandomPoint(rng);
    if (i < num_inliers) {
      q = Apply(h, r);
      q.x += static_cast<float>(rng.Normal(0, noise_px));
      q.y += static_cast<float>(rng.Normal(0, noise_px));
    }
    p.reference.push_back(r);
    p.query.push_back(q);
    p.matches.push_back({i, i});
  }
  return p;
}

TEST(HomographyFromFourPoints, ExactCorrespondencesOfRandomHomographyReprojectBelow1e6Px) {
  Rng rng = KeyedRng(1, "test.dlt");
  int solved = 0;
  for (int t = 0; t < 1000; ++t) {
    const Eigen::Matrix3d truth = RandomHomography(rng);
    Point2 src[4], dst[4];
    for (int k = 0; k < 4; ++k) {
      src[k] = RandomPoint(rng);
      dst[k] = Apply(truth, src[k]);
    }
    Eigen::Matrix3d h;
    if (!HomographyFromFourPoints(src, dst, &h)) continue;
    ++solved;
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d p = h * Eigen::Vector3d(src[k].x, src[k].y, 1.0);
      EXPECT_LT(std::hypot(p.x() / p.z() - dst[k].x, p.y() / p.z() - dst[k].y), 1e-6);
    }
  }
  EXPECT_GT(solved, 990);  // only near-collinear random samples are skipped
}

// OpenCV solves the unnormalised 8x8 system and reprojects its own points to about 1e-4 px, so
// the two are compared on where they send points across the image, at 1e-3 px.
TEST(HomographyFromFourPoints, AgreesWithOpenCvGetPerspectiveTransform) {
  Rng rng = KeyedRng(2, "test.dlt");
  for (int t = 0; t < 100; ++t) {
    const Eigen::Matrix3d truth = RandomHomography(rng);
    Point2 src[4], dst[4];
    for (int k = 0; k < 4; ++k) {
      src[k] = RandomPoint(rng);
      dst[k] = Apply(truth, src[k]);
    }
    Eigen::Matrix3d h;
    if (!HomographyFromFourPoints(src, dst, &h)) continue;
    const cv::Mat cv_mat = cv::getPerspectiveTransform(src, dst);
    Eigen::Matrix3d cv_h;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) cv_h(r, c) = cv_mat.at<double>(r, c);
    }
    for (float y = 0; y <= kHeightPx; y += 32) {
      for (float x = 0; x <= kWidthPx; x += 32) {
        const Point2 ours = Apply(h, Point2(x, y)), theirs = Apply(cv_h, Point2(x, y));
        EXPECT_LT(std::hypot(ours.x - theirs.x, ours.y - theirs.y), 1e-3);
      }
    }
  }
}

TEST(HomographyFromFourPoints, DegenerateSamplesAreRejected) {
  const Point2 square[4] = {{10, 10}, {100, 10}, {100, 90}, {10, 90}};
  const Point2 collinear[4] = {{10, 10}, {50, 50}, {90, 90}, {10, 90}};
  const Point2 nearly_collinear[4] = {{10, 10}, {50, 50.0001f}, {90, 90}, {10, 90}};
  const Point2 repeated[4] = {{10, 10}, {10, 10}, {100, 90}, {10, 90}};
  Eigen::Matrix3d h;
  EXPECT_TRUE(HomographyFromFourPoints(square, square, &h));
  EXPECT_TRUE(h.isApprox(Eigen::Matrix3d::Identity(), 1e-12));
  EXPECT_FALSE(HomographyFromFourPoints(collinear, square, &h));
  EXPECT_FALSE(HomographyFromFourPoints(square, collinear, &h));
  EXPECT_FALSE(HomographyFromFourPoints(nearly_collinear, square, &h));
  EXPECT_FALSE(HomographyFromFourPoints(repeated, square, &h));
}

TEST(HomographyLeastSquares, ExactCorrespondencesGiveTheHomographyBack) {
  Rng rng = KeyedRng(3, "test.dlt");
  const Eigen::Matrix3d truth = RandomHomography(rng);
  std::vector<float> rx, ry, qx, qy;
  for (int i = 0; i < 30; ++i) {
    const Point2 r = RandomPoint(rng), q = Apply(truth, r);
    rx.push_back(r.x);
    ry.push_back(r.y);
    qx.push_back(q.x);
    qy.push_back(q.y);
  }
  Eigen::Matrix3d h;
  ASSERT_TRUE(HomographyLeastSquares(rx.data(), ry.data(), qx.data(), qy.data(), nullptr, 30, &h));
  for (int i = 0; i < 30; ++i) {
    const Point2 p = Apply(h, Point2(rx[i], ry[i]));
    EXPECT_LT(std::hypot(p.x - qx[i], p.y - qy[i]), 1e-3);  // inputs are float
  }
}

TEST(RansacSample, UniformOverOrderedFourTuplesOfDistinctIndices) {
  // n = 6: 360 ordered 4-tuples of distinct indices, 1000 expected draws each.
  constexpr uint32_t kN = 6;
  std::vector<int> counts(kN * kN * kN * kN, 0);
  constexpr uint32_t kDraws = 360000;
  for (uint32_t d = 0; d < kDraws; ++d) {
    uint32_t idx[4];
    RansacSample(/*seed=*/77, d, kN, idx);
    for (int a = 0; a < 4; ++a) {
      ASSERT_LT(idx[a], kN);
      for (int b = 0; b < a; ++b) ASSERT_NE(idx[a], idx[b]) << "draw " << d;
    }
    ++counts[((idx[0] * kN + idx[1]) * kN + idx[2]) * kN + idx[3]];
  }
  double chi_square = 0;
  int tuples = 0;
  for (int c : counts) {
    if (c == 0) continue;
    ++tuples;
    chi_square += (c - 1000.0) * (c - 1000.0) / 1000.0;
  }
  EXPECT_EQ(tuples, 360);
  // 359 degrees of freedom: mean 359, standard deviation 26.8; this bound is 6 sigma.
  EXPECT_LT(chi_square, 520.0);
}

TEST(RansacSample, RejectionPathStaysDistinctAndUnbiased) {
  // n = 3 * 2^30: the first digit is floor(3 w / 4) of a 32-bit word w, so without the rejection
  // test digits divisible by 3 would get two words each and the others one (1/2 of the draws
  // instead of 1/3); with it a quarter of the words are rejected and redrawn under a new key.
  constexpr uint32_t kN = 3u << 30;
  int by_residue[3] = {0, 0, 0};
  constexpr int kDraws = 30000;
  for (uint32_t d = 0; d < kDraws; ++d) {
    uint32_t idx[4];
    RansacSample(/*seed=*/5, d, kN, idx);
    for (int a = 0; a < 4; ++a) {
      ASSERT_LT(idx[a], kN);
      for (int b = 0; b < a; ++b) ASSERT_NE(idx[a], idx[b]);
    }
    ++by_residue[idx[0] % 3];
  }
  // Binomial(30000, 1/3): standard deviation 82; the bound is 6 sigma.
  for (int count : by_residue) EXPECT_NEAR(count, kDraws / 3, 6 * 82);
}

TEST(RansacSample, DifferentSeedsGiveDifferentStreams) {
  int same = 0;
  for (uint32_t d = 0; d < 1000; ++d) {
    uint32_t a[4], b[4];
    RansacSample(1, d, 200, a);
    RansacSample(2, d, 200, b);
    same += std::equal(a, a + 4, b) ? 1 : 0;
  }
  EXPECT_LE(same, 2);
}

TEST(EstimateHomographyRansac, FewerThanFourMatchesGiveZeroInliers) {
  Rng rng = KeyedRng(4, "test.ransac");
  for (int n = 0; n < 4; ++n) {
    const Problem p = MakeProblem(rng, n, n, 0.0);
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
    const Problem p = MakeProblem(rng, n, n / 2, 1.0);
    const HomographyResult result = EstimateHomographyRansac(p.query, p.reference, p.matches, {}, t);
    ASSERT_EQ(static_cast<int>(result.inlier_mask.size()), n);
    EXPECT_EQ(std::accumulate(result.inlier_mask.begin(), result.inlier_mask.end(), 0),
              result.inliers);
    const int true_found = std::accumulate(result.inlier_mask.begin(),
                                           result.inlier_mask.begin() + p.num_inliers, 0);
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
    const Problem p = MakeProblem(rng, n, inliers, 1.0);
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
  const Problem p = MakeProblem(rng, 120, 40, 1.0);
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
    const Problem p = MakeProblem(rng, 20 + 7 * t, 5 + 3 * t, 1.0);
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
  explicit SoaMatches(const Problem& p) {
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
    const Problem p = MakeProblem(rng, n, n * (t % 4) / 4, 1.0);
    const SoaMatches m(p);
    for (const std::vector<RansacOptions>* set : {&variants, &crowd}) {
      const int count = static_cast<int>(set->size());
      std::vector<int> inliers(count, -1), untimed(count, -1);
      std::vector<int64_t> alone_ns(count, -1);
      int64_t total_ns = -1;
      counter.Count(m.ref_x.data(), m.ref_y.data(), m.query_x.data(), m.query_y.data(), m.size(), set->data(),
                    count, 1000 + t, inliers.data(), alone_ns.data(), &total_ns);
      counter.Count(m.ref_x.data(), m.ref_y.data(), m.query_x.data(), m.query_y.data(), m.size(), set->data(),
                    count, 1000 + t, untimed.data(), nullptr, nullptr);
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
    Problem p = MakeProblem(rng, n, n, 0.1);  // every match on the homography, to 0.1 px
    for (const bool outlier : {false, true}) {
      if (outlier) p.query.back().x += 40;  // one match far off: n - 1 inliers at best
      const SoaMatches m(p);
      int inliers[2] = {-1, -1};
      counter.Count(m.ref_x.data(), m.ref_y.data(), m.query_x.data(), m.query_y.data(), m.size(), variants.data(),
                    2, 500 + t, inliers, nullptr, nullptr);
      for (int v = 0; v < 2; ++v) {
        EXPECT_EQ(inliers[v], outlier ? n - 1 : n) << "problem " << t << ", variant " << v;
        EXPECT_EQ(inliers[v], RansacHomographySoa(m.ref_x.data(), m.ref_y.data(), m.query_x.data(), m.query_y.data(),
                                                  m.size(), variants[v], 500 + t, nullptr, nullptr));
      }
      if (outlier) {
        EXPECT_EQ(counter.hypotheses_scored(), variants[0].trials) << "a search that cannot complete scores every trial";
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
    const Problem p = MakeProblem(rng, 150, 60, 1.5);
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
    const Problem p = MakeProblem(rng, 150, 60, 1.0);
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

TEST(RansacOptions, HoldsThePapersDefaultsFromItsTableAndChecksEveryBound) {
  const RansacOptions options;
  EXPECT_EQ(options.trials, 100);  // paper, section 5.2
  EXPECT_EQ(options.inlier_threshold_px, 5.0);
  EXPECT_EQ(options.local_optimisation_refits, 0);
  ExpectConstructedHoldsTheTableDefaults<RansacOptions>();
  EXPECT_EQ(ExpectEveryBoundCrossedIsNamedByCheck<RansacOptions>(), 5);
}

TEST(EstimateHomographyRansac, OutOfRangeMatchIsRejected) {
  const std::vector<Point2> points(4, Point2(1, 1));
  EXPECT_THROW(EstimateHomographyRansac(points, points, {{0, 4}}, {}, 1), std::logic_error);
}

}  // namespace
}  // namespace hoilcd
