// RANSAC homography between matched 2-D point sets (paper 4.1.3, 4.2.2, 5.2): the loop of
// core/optim/ransac.h driving the homography model of homography.h, on matches given as index
// pairs into two point sets or as matched coordinates.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "hoilcd/core/estimators/homography.h"
#include "hoilcd/core/geometry/point.h"
#include "hoilcd/core/optim/ransac.h"

namespace hoilcd {

// A match: indices into the query and the reference point sets.
struct Correspondence {
  int query;
  int reference;
};

inline bool operator==(const Correspondence& a, const Correspondence& b) {
  return a.query == b.query && a.reference == b.reference;
}

struct HomographyResult {
  int inliers = 0;                                                   // size of the best inlier set
  Eigen::Matrix3d reference_to_query = Eigen::Matrix3d::Identity();  // best model, H(2,2) = 1
  std::vector<uint8_t> inlier_mask;                                  // one 0/1 entry per match
};

// Homography maps reference points to query points; fewer than 4 matches => 0 inliers.
// Deterministic given seed: sample d (d = 0, 1, ...) is RansacSample(seed, d, matches). A sample is
// degenerate if three of its points are (nearly) collinear in either image or if it keeps the
// orientation of some point triplets but not of others (as OpenCV's checkSubset).
HomographyResult EstimateHomographyRansac(const std::vector<Point2>& query, const std::vector<Point2>& reference,
                                          const std::vector<Correspondence>& matches, const RansacOptions& options,
                                          uint64_t seed);

// EstimateHomographyRansac(...).inliers, without the model and the inlier mask (for scoring).
int CountRansacInliers(const std::vector<Point2>& query, const std::vector<Point2>& reference,
                       const std::vector<Correspondence>& matches, const RansacOptions& options, uint64_t seed);

// The same loop on matched coordinates as structure of arrays (count entries each); returns the
// inlier count. best_h and inlier_mask (count entries) may be null. Options are not re-checked.
int RansacHomographySoa(const float* ref_x, const float* ref_y, const float* query_x, const float* query_y, int count,
                        const RansacOptions& options, uint64_t seed, Eigen::Matrix3d* best_h, uint8_t* inlier_mask);

// RansacHomographySoa's inlier counts under several variants of the options at once, reusing
// scratch buffers between calls (one counter per thread): RansacVariants (ransac.h) with the
// homography, so inliers[v] equals RansacHomographySoa(..., variants[v], seed, nullptr, nullptr)
// and the variants that draw the same samples score one stream. Options are not re-checked.
// alone_ns and total_ns as in RansacVariants::Count, where gathering the matches, ~1 % of a call,
// is charged to the first stream's variants.
class RansacCounter {
 public:
  void Count(const float* ref_x, const float* ref_y, const float* query_x, const float* query_y, int count,
             const RansacOptions* variants, int num_variants, uint64_t seed, int* inliers, int64_t* alone_ns,
             int64_t* total_ns);
  // Hypotheses the last Count drew and solved, over all its streams.
  int hypotheses_scored() const { return variants_.hypotheses_scored(); }

 private:
  std::vector<float> quads_;
  RansacVariants<HomographyEstimator> variants_;
};

}  // namespace hoilcd
