#include "hoilcd/core/matching/track_aware_matching.h"

#include <cmath>
#include <map>

#include <gtest/gtest.h>

#include "option_properties.h"

namespace hoilcd {
namespace {

// One person's bottom contour: a point per column in [x0, x1], y = base + shape(column).
void AddPerson(std::vector<HoiFeature>* features, int track_id, int x0, int x1, double base_y, double (*shape)(int),
               Point2 offset) {
  for (int x = x0; x <= x1; ++x) {
    const double y = std::round(base_y + shape(x - x0));
    features->push_back({Point2(static_cast<float>(x) + offset.x, static_cast<float>(y) + offset.y), track_id});
  }
}

double Arch(int i) { return -0.02 * (i - 20) * (i - 20); }
double Vee(int i) { return std::abs(i - 15) * 0.8; }
double Step(int i) { return i < 25 ? 0.0 : 6.0; }

// Three seated persons; track ids start at `first_id`; added in reverse order so the grouping
// has to sort them.
std::vector<HoiFeature> ThreePersons(int first_id, Point2 offset) {
  std::vector<HoiFeature> features;
  AddPerson(&features, first_id + 2, 170, 220, 160.0, Step, offset);
  AddPerson(&features, first_id + 1, 100, 130, 120.0, Vee, offset);
  AddPerson(&features, first_id, 30, 70, 150.0, Arch, offset);
  return features;
}

TEST(TrackAwareMatching, ShiftedPersonsGiveOnlyCorrectCorrespondencesAndAllRansacInliers) {
  const Point2 offset(12.0f, 3.0f);
  const std::vector<HoiFeature> query = ThreePersons(1, Point2(0, 0));
  const std::vector<HoiFeature> reference = ThreePersons(7, offset);
  const std::vector<Correspondence> matches = TrackAwareCorrespondences(query, reference, TrackAwareOptions());
  // Arc-length sampling skips a few points next to steep steps of a contour.
  ASSERT_GE(matches.size(), query.size() * 9 / 10);
  for (const Correspondence& m : matches) {
    const HoiFeature& q = query[static_cast<size_t>(m.query)];
    const HoiFeature& r = reference[static_cast<size_t>(m.reference)];
    EXPECT_EQ(r.track_id, q.track_id + 6) << "persons crossed";
    EXPECT_EQ(r.point - q.point, offset);
  }
  EXPECT_EQ(ScoreTrackAwarePair(query, reference, TrackAwareOptions(), RansacOptions(), 5, 0, 1),
            static_cast<int>(matches.size()));
}

TEST(TrackAwareMatching, ExtraPersonDoesNotDisturbTheCommonPairs) {
  const Point2 offset(-8.0f, 0.0f);
  const std::vector<HoiFeature> query = ThreePersons(1, Point2(0, 0));
  std::vector<HoiFeature> reference = ThreePersons(20, offset);
  AddPerson(&reference, 40, 232, 252, 100.0, Vee, Point2(0, 0));
  const auto persons = PairPersons(GroupPersonContours(query, TrackAwareOptions()),
                                   GroupPersonContours(reference, TrackAwareOptions()), TrackAwareOptions());
  ASSERT_EQ(persons.matches.size(), 3u);
  EXPECT_EQ(persons.unmatched_cols, std::vector<int>{3});
  const std::vector<Correspondence> matches = TrackAwareCorrespondences(query, reference, TrackAwareOptions());
  ASSERT_EQ(matches.size(), TrackAwareCorrespondences(query, ThreePersons(20, offset), TrackAwareOptions()).size());
  for (const Correspondence& m : matches) {
    const HoiFeature& q = query[static_cast<size_t>(m.query)];
    const HoiFeature& r = reference[static_cast<size_t>(m.reference)];
    EXPECT_EQ(r.track_id, q.track_id + 19);
    EXPECT_EQ(r.point - q.point, offset);
  }
}

TEST(TrackAwareMatching, UnequalContoursMatchAtEqualFractionsOfTheirLength) {
  // The reference person is the query person stretched to twice the width: query column i pairs
  // with reference column 2i (both contours flat, so arc length is proportional to x).
  std::vector<HoiFeature> query, reference;
  for (int x = 50; x <= 60; ++x) query.push_back({Point2(static_cast<float>(x), 150.0f), 1});
  for (int x = 50; x <= 70; ++x) reference.push_back({Point2(static_cast<float>(x), 150.0f), 2});
  const auto matches = TrackAwareCorrespondences(query, reference, TrackAwareOptions());
  ASSERT_EQ(matches.size(), 11u);
  for (const Correspondence& m : matches) {
    EXPECT_EQ(reference[static_cast<size_t>(m.reference)].point.x - 50.0f,
              2.0f * (query[static_cast<size_t>(m.query)].point.x - 50.0f));
  }
}

TEST(TrackAwareMatching, SameShapeCostsLessThanADifferentShapeAtTheSamePlace) {
  std::vector<HoiFeature> arch, arch_shifted, vee;
  AddPerson(&arch, 1, 30, 70, 150.0, Arch, Point2(0, 0));
  AddPerson(&arch_shifted, 2, 30, 70, 150.0, Arch, Point2(5, 0));
  AddPerson(&vee, 3, 30, 70, 150.0, Vee, Point2(0, 0));
  const TrackAwareOptions options;
  const PersonContour a = GroupPersonContours(arch, options)[0];
  const double same = PersonPairCost(a, GroupPersonContours(arch_shifted, options)[0], options);
  const double other = PersonPairCost(a, GroupPersonContours(vee, options)[0], options);
  EXPECT_NEAR(same, 5.0, 1e-9);  // only the centre offset
  EXPECT_GT(other, same);
}

TEST(TrackAwareMatching, PersonsTooFarApartStayUnpaired) {
  const std::vector<HoiFeature> query = ThreePersons(1, Point2(0, 0));
  const std::vector<HoiFeature> reference = ThreePersons(7, Point2(0, 0));
  TrackAwareOptions options;
  // Moved 100 px down: every pair costs more than max_pair_cost (80).
  EXPECT_EQ(TrackAwareCorrespondences(query, ThreePersons(7, Point2(0, 100)), options).size(), 0u);
  EXPECT_GT(TrackAwareCorrespondences(query, reference, options).size(), 0u);
}

TEST(TrackAwareMatching, APreparedFrameScoresEveryReferenceAsIfPreparedForThatPairAlone) {
  // dlcd-track prepares each frame once and scores it against many: one prepared query must give
  // each reference the score of its pair from the raw features, in any order.
  const TrackAwareOptions options;
  const RansacOptions ransac;
  const std::vector<HoiFeature> query = ThreePersons(1, Point2(0, 0));
  std::vector<std::vector<HoiFeature>> references;
  for (int k = 0; k < 6; ++k) references.push_back(ThreePersons(10 * k, Point2(3.0f * k - 7.0f, 0.5f * k)));
  references[4].erase(references[4].begin(), references[4].begin() + 45);  // a person missing
  const TrackAwareFrame prepared = PrepareTrackAwareFrame(query, options);
  ASSERT_EQ(prepared.points.size(), query.size());
  ASSERT_EQ(prepared.persons.size(), 3u);
  for (int pass = 0; pass < 2; ++pass) {
    for (int k = 5; k >= 0; --k) {
      const int expected = ScoreTrackAwarePair(query, references[k], options, ransac, 9, 3, k);
      EXPECT_GT(expected, 0) << k;
      EXPECT_EQ(ScoreTrackAwarePair(prepared, PrepareTrackAwareFrame(references[k], options), options, ransac, 9, 3, k),
                expected)
          << k;
    }
  }
}

TEST(TrackAwareMatching, EmptyOrTinyInputsScoreZero) {
  const std::vector<HoiFeature> persons = ThreePersons(1, Point2(0, 0));
  const TrackAwareOptions options;
  const RansacOptions ransac;
  const std::vector<HoiFeature> none;
  EXPECT_EQ(ScoreTrackAwarePair(none, none, options, ransac, 1, 0, 1), 0);
  EXPECT_EQ(ScoreTrackAwarePair(persons, none, options, ransac, 1, 0, 1), 0);
  EXPECT_EQ(ScoreTrackAwarePair(none, persons, options, ransac, 1, 0, 1), 0);
  // Two points per person are below min_points_per_person: nobody to pair.
  const std::vector<HoiFeature> tiny = {{Point2(10, 10), 1}, {Point2(11, 10), 1}};
  EXPECT_TRUE(GroupPersonContours(tiny, options).empty());
  EXPECT_EQ(ScoreTrackAwarePair(tiny, tiny, options, ransac, 1, 0, 1), 0);
}

TEST(TrackAwareMatching, GroupingSortsEachPersonAlongXWithAProfileOfTheRequestedLength) {
  const TrackAwareOptions options;
  const std::vector<HoiFeature> features = ThreePersons(1, Point2(0, 0));
  const std::vector<PersonContour> persons = GroupPersonContours(features, options);
  ASSERT_EQ(persons.size(), 3u);
  for (size_t p = 0; p < persons.size(); ++p) {
    EXPECT_EQ(persons[p].track_id, static_cast<int>(p) + 1);
    EXPECT_EQ(persons[p].profile_px.size(), static_cast<size_t>(options.profile_samples));
    for (size_t i = 1; i < persons[p].indices.size(); ++i) {
      EXPECT_LT(features[static_cast<size_t>(persons[p].indices[i - 1])].point.x,
                features[static_cast<size_t>(persons[p].indices[i])].point.x);
      EXPECT_GT(persons[p].arc_length_px[i], persons[p].arc_length_px[i - 1]);
    }
  }
  EXPECT_DOUBLE_EQ(persons[0].x_min_px, 30.0);
  EXPECT_DOUBLE_EQ(persons[0].x_max_px, 70.0);
}

TEST(TrackAwareMatching, SeedKeyDiffersFromPairToPairAndScoreIsRepeatable) {
  EXPECT_NE(TrackAwarePairSeed(1, 2, 3), TrackAwarePairSeed(1, 3, 2));
  EXPECT_NE(TrackAwarePairSeed(1, 2, 3), TrackAwarePairSeed(2, 2, 3));
  const std::vector<HoiFeature> query = ThreePersons(1, Point2(0, 0));
  std::vector<HoiFeature> reference = ThreePersons(7, Point2(4, 2));
  for (size_t i = 0; i < reference.size(); i += 3) reference[i].point.y += 9.0f;  // outliers
  const TrackAwareOptions options;
  const int first = ScoreTrackAwarePair(query, reference, options, RansacOptions(), 9, 4, 5);
  EXPECT_EQ(first, ScoreTrackAwarePair(query, reference, options, RansacOptions(), 9, 4, 5));
  EXPECT_GT(first, static_cast<int>(query.size()) / 2);
  EXPECT_LT(first, static_cast<int>(query.size()));
}

TEST(TrackAwareMatching, MatchTrackAwarePairGivesTheCorrespondencesAndInliersBehindTheScore) {
  // The report's gallery draws these: the contour correspondences, and as many RANSAC inliers
  // (from the same stream) as ScoreTrackAwarePair counts, with some correspondences rejected.
  const TrackAwareOptions options;
  const RansacOptions ransac;
  const std::vector<HoiFeature> query = ThreePersons(1, Point2(0, 0));
  std::vector<HoiFeature> reference = ThreePersons(7, Point2(4, 2));
  for (size_t i = 0; i < reference.size(); i += 3) reference[i].point.y += 9.0f;  // outliers
  const TrackAwareFrame q = PrepareTrackAwareFrame(query, options), r = PrepareTrackAwareFrame(reference, options);
  const PairMatches pair = MatchTrackAwarePair(q, r, options, ransac, 9, 4, 5);
  EXPECT_EQ(pair.matches, TrackAwareCorrespondences(query, reference, options));
  ASSERT_EQ(pair.inlier.size(), pair.matches.size());
  int marked = 0;
  for (uint8_t inlier : pair.inlier) marked += inlier;
  EXPECT_EQ(marked, pair.inliers);
  EXPECT_EQ(pair.inliers, ScoreTrackAwarePair(q, r, options, ransac, 9, 4, 5));
  EXPECT_GT(pair.inliers, 0);
  EXPECT_LT(pair.inliers, static_cast<int>(pair.matches.size()));
  // No persons: no matches, no inliers.
  const PairMatches empty = MatchTrackAwarePair(q, PrepareTrackAwareFrame({}, options), options, ransac, 9, 4, 5);
  EXPECT_TRUE(empty.matches.empty());
  EXPECT_TRUE(empty.inlier.empty());
  EXPECT_EQ(empty.inliers, 0);
}

TEST(TrackAwareMatching, OptionChecksNameTheBadField) {
  TrackAwareOptions options;
  EXPECT_EQ(options.Check(), "");
  options.profile_samples = 1;
  EXPECT_NE(options.Check().find("profile_samples"), std::string::npos);
  options = TrackAwareOptions();
  options.max_pair_cost = 0.0;
  EXPECT_NE(options.Check().find("max_pair_cost"), std::string::npos);
  options = TrackAwareOptions();
  options.shape_weight = -1.0;
  EXPECT_NE(options.Check().find("shape_weight"), std::string::npos);
  options = TrackAwareOptions();
  options.min_points_per_person = 0;
  EXPECT_NE(options.Check().find("min_points_per_person"), std::string::npos);
}

TEST(TrackAwareMatching, OptionsHoldTheirTablesDefaultsAndEveryBoundIsChecked) {
  ExpectConstructedHoldsTheTableDefaults<TrackAwareOptions>();
  EXPECT_EQ(ExpectEveryBoundCrossedIsNamedByCheck<TrackAwareOptions>(), 7);
}

}  // namespace
}  // namespace hoilcd
