// RANSAC homography between matched 2-D point sets (paper 4.1.3, 4.2.2, 5.2): exactly N trials of
// a 4-point DLT, degenerate samples skipped, inlier if the reprojection error of the reference
// point mapped into the query image is below a threshold. Optional LO-RANSAC refits (Chum 2003).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core/types.hpp>

#include "hoilcd/core/geometry/point.h"
#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

// A match: indices into the query and the reference point sets.
struct Correspondence {
  int query;
  int reference;
};

inline bool operator==(const Correspondence& a, const Correspondence& b) {
  return a.query == b.query && a.reference == b.reference;
}

// Defaults and ranges: Table() in homography_ransac.cpp.
struct RansacOptions {
  int trials;                      // exact number of hypotheses (paper), no adaptive stop
  bool redraw_degenerate_samples;  // a degenerate sample is redrawn (up to 10 draws per trial on
                                   // average) instead of using up its trial
  double inlier_threshold_px;      // reprojection error bound, px
  int local_optimisation_refits;   // 0 = plain RANSAC (paper); >0 = LO-RANSAC least-squares
                                   // refits on the inlier set of each new best model

  RansacOptions();  // the registered defaults
  // Every field once: name, default, unit, range, description.
  static const OptionTable<RansacOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

struct HomographyResult {
  int inliers = 0;                                                  // size of the best inlier set
  Eigen::Matrix3d reference_to_query = Eigen::Matrix3d::Identity();  // best model, H(2,2) = 1
  std::vector<uint8_t> inlier_mask;                                 // one 0/1 entry per match
};

// Homography maps reference points to query points; fewer than 4 matches => 0 inliers.
// Deterministic given seed: sample d (d = 0, 1, ...) is RansacSample(seed, d, matches). A sample is
// degenerate if three of its points are (nearly) collinear in either image or if it keeps the
// orientation of some point triplets but not of others (as OpenCV's checkSubset).
HomographyResult EstimateHomographyRansac(const std::vector<Point2>& query,
                                          const std::vector<Point2>& reference,
                                          const std::vector<Correspondence>& matches,
                                          const RansacOptions& options, uint64_t seed);

// EstimateHomographyRansac(...).inliers, without the model and the inlier mask (for scoring).
int CountRansacInliers(const std::vector<Point2>& query, const std::vector<Point2>& reference,
                       const std::vector<Correspondence>& matches, const RansacOptions& options, uint64_t seed);

// The same loop on matched coordinates as structure of arrays (count entries each); returns the
// inlier count. best_h and inlier_mask (count entries) may be null. Options are not re-checked.
int RansacHomographySoa(const float* ref_x, const float* ref_y, const float* query_x,
                        const float* query_y, int count, const RansacOptions& options,
                        uint64_t seed, Eigen::Matrix3d* best_h, uint8_t* inlier_mask);

// RansacHomographySoa's inlier counts under several variants of the options at once, reusing
// scratch buffers between calls (one counter per thread). Variants with the same trials and
// redraw_degenerate_samples draw the same samples, so those are drawn and solved once and the
// hypotheses scored under each variant's threshold and refits: inliers[v] equals
// RansacHomographySoa(..., variants[v], seed, nullptr, nullptr). Options are not re-checked.
// When alone_ns is not null (then total_ns must not be), alone_ns[v] gets what variant v costs
// alone (drawing and solving its samples, and its own scoring; gathering the matches, ~1 % of a
// call, is charged to the first stream's variants) and *total_ns the whole call, in ns; both are
// 0 below 4 matches, where nothing is timed. A stream stops early once every match is an inlier
// of each of its variants' best models: nothing later can change their results.
class RansacCounter {
 public:
  void Count(const float* ref_x, const float* ref_y, const float* query_x, const float* query_y, int count,
             const RansacOptions* variants, int num_variants, uint64_t seed, int* inliers, int64_t* alone_ns,
             int64_t* total_ns);
  // Hypotheses the last Count drew and solved, over all its streams.
  int hypotheses_scored() const { return hypotheses_scored_; }

 private:
  std::vector<float> quads_;
  std::vector<std::vector<uint8_t>> lo_masks_;  // one per variant
  std::vector<float> hypotheses_;               // one chunk of a stream
  std::vector<char> scored_;                    // per variant: already in a group
  int hypotheses_scored_ = 0;
};

// Draw `draw` of the RANSAC stream `seed` over n >= 4 matches: four distinct indices in [0, n),
// uniform over ordered 4-tuples, from the counter-based words CounterWord(seed, 4 draw + k)
// (random.h). The loop draws eight samples at once in vector lanes with the same result.
void RansacSample(uint64_t seed, uint32_t draw, uint32_t n, uint32_t idx[4]);

// 4-point DLT on normalised homogeneous coordinates, solved in closed form (for 4 points the DLT
// null vector is unique and equals the unit-square-to-quad composition); maps src[i] to dst[i].
// Returns false for degenerate (collinear / near-singular) samples.
bool HomographyFromFourPoints(const Point2 src[4], const Point2 dst[4], Eigen::Matrix3d* h);

// Least-squares DLT on n >= 4 correspondences (Hartley normalisation, AᵀA from moment sums,
// h(2,2) fixed to 1 in normalised coordinates, 8x8 LDLT), used by the LO-RANSAC refits; `use`
// (may be null) selects the correspondences. Returns false when the fit is degenerate.
bool HomographyLeastSquares(const float* ref_x, const float* ref_y, const float* query_x,
                            const float* query_y, const uint8_t* use, int count,
                            Eigen::Matrix3d* h);

}  // namespace hoilcd
