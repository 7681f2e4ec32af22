// Track-aware DLCD matching: instead of coordinate nearest neighbours over all HOI points, persons
// are paired first (linear assignment on a bottom-contour shape + position cost) and each pair's
// contours give point correspondences at equal fractions of their length, fed to the same RANSAC.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "hoilcd/core/estimators/homography_ransac.h"
#include "hoilcd/core/features/hoi_features.h"
#include "hoilcd/core/matching/matching.h"
#include "hoilcd/core/tracking/lapjv.h"
#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

// Defaults and ranges: Table() in track_aware_matching.cpp.
struct TrackAwareOptions {
  int min_points_per_person;  // points; persons with fewer HOI points are ignored
  int profile_samples;        // samples of the contour profile compared between persons
  double position_weight;     // cost per px of offset of the contour centre (x and mean y)
  double width_weight;        // cost per px of difference in contour width (x-extent)
  double shape_weight;        // cost per px of mean difference of the centred profiles
  double max_pair_cost;       // persons whose pair cost exceeds this stay unpaired, px

  TrackAwareOptions();  // the registered defaults
  // Every field once: name, default, unit, range, description.
  static const OptionTable<TrackAwareOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

// One person's bottom contour in one frame.
struct PersonContour {
  int track_id = 0;
  std::vector<int> indices;           // into the frame's features, sorted by x (then y)
  std::vector<double> arc_length_px;  // cumulative polyline length at each point, from 0, px
  double x_min_px = 0, x_max_px = 0;  // x-extent, px
  double mean_y_px = 0;               // mean row of the points, px
  std::vector<double> profile_px;     // y - mean_y at profile_samples evenly spaced x, px
};

// Groups a frame's HOI points by track id (ascending id), each group ordered along x.
std::vector<PersonContour> GroupPersonContours(const std::vector<HoiFeature>& features,
                                               const TrackAwareOptions& options);

// position_weight * (|centre x diff| + |mean y diff|) + width_weight * |width diff|
// + shape_weight * mean |profile diff|.
double PersonPairCost(const PersonContour& query, const PersonContour& reference, const TrackAwareOptions& options);

// Query persons (rows) paired with reference persons (columns) by LinearAssignment on
// PersonPairCost with cost limit max_pair_cost.
Assignment PairPersons(const std::vector<PersonContour>& query, const std::vector<PersonContour>& reference,
                       const TrackAwareOptions& options);

// For each person pair, min(n_q, n_r) correspondences: at fractions i / (n - 1) of each contour's
// polyline length, the point nearest that arc position on either side (consecutive duplicates
// dropped). Indices refer to the input feature vectors; pairs come person pair by person pair.
std::vector<Correspondence> TrackAwareCorrespondences(const std::vector<HoiFeature>& query,
                                                      const std::vector<HoiFeature>& reference,
                                                      const TrackAwareOptions& options);
// The same from contours already grouped (GroupPersonContours).
std::vector<Correspondence> TrackAwareCorrespondences(const std::vector<PersonContour>& query,
                                                      const std::vector<PersonContour>& reference,
                                                      const TrackAwareOptions& options);

// A frame made ready for scoring against many others: its points and its persons' contours,
// grouped once instead of once per pair.
struct TrackAwareFrame {
  std::vector<Point2> points;          // the features' points, in feature order
  std::vector<PersonContour> persons;  // GroupPersonContours(features)
};
TrackAwareFrame PrepareTrackAwareFrame(const std::vector<HoiFeature>& features, const TrackAwareOptions& options);

// The RANSAC stream of one pair: the key KeyedRng(seed, "ransac.track_aware", query_id,
// reference_id) would use, so track-aware draws never coincide with the plain method's.
uint64_t TrackAwarePairSeed(uint64_t seed, int query_id, int reference_id);

// TrackAwareCorrespondences -> EstimateHomographyRansac(seed TrackAwarePairSeed(...)); returns
// the inlier count (0 for fewer than 4 correspondences, e.g. empty frames).
int ScoreTrackAwarePair(const std::vector<HoiFeature>& query, const std::vector<HoiFeature>& reference,
                        const TrackAwareOptions& options, const RansacOptions& ransac_options, uint64_t seed,
                        int query_id, int reference_id);
// The same score from prepared frames (PrepareTrackAwareFrame with the same options).
int ScoreTrackAwarePair(const TrackAwareFrame& query, const TrackAwareFrame& reference,
                        const TrackAwareOptions& options, const RansacOptions& ransac_options, uint64_t seed,
                        int query_id, int reference_id);

// The matches behind ScoreTrackAwarePair's score, for pictures (the report's gallery): the
// contour correspondences (person pair by person pair) and which of them RANSAC counts as
// inliers, from the same stream; inliers equals ScoreTrackAwarePair(...) with the same arguments.
PairMatches MatchTrackAwarePair(const TrackAwareFrame& query, const TrackAwareFrame& reference,
                                const TrackAwareOptions& options, const RansacOptions& ransac_options, uint64_t seed,
                                int query_id, int reference_id);

}  // namespace hoilcd
