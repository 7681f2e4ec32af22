#include "hoilcd/core/matching/track_aware_matching.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/random.h"
#include "hoilcd/core/util/sizes.h"

namespace hoilcd {
namespace {

// y of the contour at column x, linearly interpolated between its points (sorted by x).
double ContourYAt(const std::vector<HoiFeature>& features, const std::vector<int>& indices, double x) {
  const auto point = [&](size_t i) { return features[static_cast<size_t>(indices[i])].point; };
  if (x <= point(0).x) return point(0).y;
  for (size_t i = 1; i < indices.size(); ++i) {
    const Point2 a = point(i - 1), b = point(i);
    if (x <= b.x) {
      const double dx = static_cast<double>(b.x) - a.x;
      const double t = dx > 0 ? (x - a.x) / dx : 1.0;
      return a.y + t * (static_cast<double>(b.y) - a.y);
    }
  }
  return point(indices.size() - 1).y;
}

// Position along the contour whose arc length is nearest `arc_px`.
size_t NearestArcPosition(const std::vector<double>& arc_length_px, double arc_px) {
  const auto it = std::lower_bound(arc_length_px.begin(), arc_length_px.end(), arc_px);
  if (it == arc_length_px.end()) return arc_length_px.size() - 1;
  const size_t i = static_cast<size_t>(it - arc_length_px.begin());
  if (i > 0 && arc_px - arc_length_px[i - 1] <= *it - arc_px) return i - 1;
  return i;
}

}  // namespace

TrackAwareOptions::TrackAwareOptions() { Table().FillDefaults(this); }

const OptionTable<TrackAwareOptions>& TrackAwareOptions::Table() {
  using O = TrackAwareOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("min_points_per_person", &O::min_points_per_person, 3, "", R::Any().AtLeast(1),
               "persons with fewer HOI points are ignored")
          // No more samples than a person's box can have columns.
          .Add("profile_samples", &O::profile_samples, 16, "", R::Closed(2, kMaxImageSidePx),
               "samples of the contour profile compared between persons")
          .Add("position_weight", &O::position_weight, 1.0, "", R::Any().AtLeast(0),
               "cost per px of offset of the contour centre (x and mean y)")
          .Add("width_weight", &O::width_weight, 0.5, "", R::Any().AtLeast(0),
               "cost per px of difference in contour width (x-extent)")
          .Add("shape_weight", &O::shape_weight, 1.0, "", R::Any().AtLeast(0),
               "cost per px of mean difference of the centred profiles")
          .Add("max_pair_cost", &O::max_pair_cost, 80.0, "px", R::Any().Above(0),
               "persons whose pair cost exceeds this stay unpaired");
  return table;
}

std::string TrackAwareOptions::Check() const { return Table().FirstProblem(*this); }

std::vector<PersonContour> GroupPersonContours(const std::vector<HoiFeature>& features,
                                               const TrackAwareOptions& options) {
  HOILCD_CHECK_MSG(options.Check().empty(), options.Check());
  std::map<int, std::vector<int>> by_track;
  for (size_t i = 0; i < features.size(); ++i) {
    by_track[features[i].track_id].push_back(static_cast<int>(i));
  }
  std::vector<PersonContour> persons;
  for (auto& [track_id, indices] : by_track) {
    if (static_cast<int>(indices.size()) < options.min_points_per_person) continue;
    std::sort(indices.begin(), indices.end(), [&](int a, int b) {
      const Point2 pa = features[static_cast<size_t>(a)].point;
      const Point2 pb = features[static_cast<size_t>(b)].point;
      return pa.x < pb.x || (pa.x == pb.x && (pa.y < pb.y || (pa.y == pb.y && a < b)));
    });
    PersonContour person;
    person.track_id = track_id;
    person.indices = indices;
    double sum_y = 0.0, arc_px = 0.0;
    for (size_t i = 0; i < indices.size(); ++i) {
      const Point2 p = features[static_cast<size_t>(indices[i])].point;
      if (i > 0) {
        const Point2 previous = features[static_cast<size_t>(indices[i - 1])].point;
        arc_px += std::hypot(static_cast<double>(p.x) - previous.x, static_cast<double>(p.y) - previous.y);
      }
      person.arc_length_px.push_back(arc_px);
      sum_y += p.y;
    }
    person.x_min_px = features[static_cast<size_t>(indices.front())].point.x;
    person.x_max_px = features[static_cast<size_t>(indices.back())].point.x;
    person.mean_y_px = sum_y / static_cast<double>(indices.size());
    for (int s = 0; s < options.profile_samples; ++s) {
      const double x = person.x_min_px + (person.x_max_px - person.x_min_px) * s / (options.profile_samples - 1);
      person.profile_px.push_back(ContourYAt(features, indices, x) - person.mean_y_px);
    }
    persons.push_back(std::move(person));
  }
  return persons;
}

double PersonPairCost(const PersonContour& query, const PersonContour& reference, const TrackAwareOptions& options) {
  HOILCD_CHECK_MSG(query.profile_px.size() == reference.profile_px.size() && !query.profile_px.empty(),
                   "contours built with different profile_samples");
  const double centre_dx = 0.5 * ((query.x_min_px + query.x_max_px) - (reference.x_min_px + reference.x_max_px));
  const double dy = query.mean_y_px - reference.mean_y_px;
  const double width_diff = (query.x_max_px - query.x_min_px) - (reference.x_max_px - reference.x_min_px);
  double shape = 0.0;
  for (size_t s = 0; s < query.profile_px.size(); ++s) {
    shape += std::abs(query.profile_px[s] - reference.profile_px[s]);
  }
  shape /= static_cast<double>(query.profile_px.size());
  return options.position_weight * (std::abs(centre_dx) + std::abs(dy)) + options.width_weight * std::abs(width_diff) +
         options.shape_weight * shape;
}

Assignment PairPersons(const std::vector<PersonContour>& query, const std::vector<PersonContour>& reference,
                       const TrackAwareOptions& options) {
  HOILCD_CHECK_MSG(options.Check().empty(), options.Check());
  std::vector<std::vector<double>> cost(query.size(), std::vector<double>(reference.size()));
  for (size_t a = 0; a < query.size(); ++a) {
    for (size_t b = 0; b < reference.size(); ++b) {
      cost[a][b] = PersonPairCost(query[a], reference[b], options);
    }
  }
  return LinearAssignment(cost, options.max_pair_cost);
}

std::vector<Correspondence> TrackAwareCorrespondences(const std::vector<HoiFeature>& query,
                                                      const std::vector<HoiFeature>& reference,
                                                      const TrackAwareOptions& options) {
  return TrackAwareCorrespondences(GroupPersonContours(query, options), GroupPersonContours(reference, options),
                                   options);
}

std::vector<Correspondence> TrackAwareCorrespondences(const std::vector<PersonContour>& query_persons,
                                                      const std::vector<PersonContour>& reference_persons,
                                                      const TrackAwareOptions& options) {
  std::vector<Correspondence> matches;
  if (query_persons.empty() || reference_persons.empty()) return matches;
  for (const auto& [a, b] : PairPersons(query_persons, reference_persons, options).matches) {
    const PersonContour& q = query_persons[static_cast<size_t>(a)];
    const PersonContour& r = reference_persons[static_cast<size_t>(b)];
    const size_t count = std::min(q.indices.size(), r.indices.size());
    for (size_t i = 0; i < count; ++i) {
      const double fraction = count == 1 ? 0.5 : static_cast<double>(i) / static_cast<double>(count - 1);
      const size_t qi = NearestArcPosition(q.arc_length_px, fraction * q.arc_length_px.back());
      const size_t ri = NearestArcPosition(r.arc_length_px, fraction * r.arc_length_px.back());
      const Correspondence match{q.indices[qi], r.indices[ri]};
      if (matches.empty() || matches.back().query != match.query || matches.back().reference != match.reference) {
        matches.push_back(match);
      }
    }
  }
  return matches;
}

TrackAwareFrame PrepareTrackAwareFrame(const std::vector<HoiFeature>& features, const TrackAwareOptions& options) {
  TrackAwareFrame frame;
  frame.points.reserve(features.size());
  for (const HoiFeature& f : features) frame.points.push_back(f.point);
  frame.persons = GroupPersonContours(features, options);
  return frame;
}

uint64_t TrackAwarePairSeed(uint64_t seed, int query_id, int reference_id) {
  return HashCombine(seed, HashString("ransac.track_aware"), static_cast<uint64_t>(query_id),
                     static_cast<uint64_t>(reference_id));
}

int ScoreTrackAwarePair(const std::vector<HoiFeature>& query, const std::vector<HoiFeature>& reference,
                        const TrackAwareOptions& options, const RansacOptions& ransac_options, uint64_t seed,
                        int query_id, int reference_id) {
  return ScoreTrackAwarePair(PrepareTrackAwareFrame(query, options), PrepareTrackAwareFrame(reference, options),
                             options, ransac_options, seed, query_id, reference_id);
}

int ScoreTrackAwarePair(const TrackAwareFrame& query, const TrackAwareFrame& reference,
                        const TrackAwareOptions& options, const RansacOptions& ransac_options, uint64_t seed,
                        int query_id, int reference_id) {
  // CountRansacInliers checks the options (for pairs without matches too) and gives 0 below 4.
  const std::vector<Correspondence> matches = TrackAwareCorrespondences(query.persons, reference.persons, options);
  return CountRansacInliers(query.points, reference.points, matches, ransac_options,
                            TrackAwarePairSeed(seed, query_id, reference_id));
}

PairMatches MatchTrackAwarePair(const TrackAwareFrame& query, const TrackAwareFrame& reference,
                                const TrackAwareOptions& options, const RansacOptions& ransac_options, uint64_t seed,
                                int query_id, int reference_id) {
  PairMatches out;
  out.matches = TrackAwareCorrespondences(query.persons, reference.persons, options);
  // EstimateHomographyRansac checks the options and gives 0 inliers below 4 matches, as the scorer.
  HomographyResult ransac = EstimateHomographyRansac(query.points, reference.points, out.matches, ransac_options,
                                                     TrackAwarePairSeed(seed, query_id, reference_id));
  out.inlier = std::move(ransac.inlier_mask);
  out.inliers = ransac.inliers;
  return out;
}

}  // namespace hoilcd
