// The homography model (paper 4.1.3): the closed-form 4-point solver, the least-squares DLT refit
// and the inlier kernels, as the estimator the RANSAC loop (core/optim/ransac.h) drives. A
// homography maps reference points to query points.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "hoilcd/core/geometry/point.h"
#include "hoilcd/core/optim/ransac.h"

namespace hoilcd {

// 4-point DLT on normalised homogeneous coordinates, solved in closed form (for 4 points the DLT
// null vector is unique and equals the unit-square-to-quad composition); maps src[i] to dst[i].
// Returns false for degenerate (collinear / near-singular) samples.
bool HomographyFromFourPoints(const Point2 src[4], const Point2 dst[4], Eigen::Matrix3d* h);

// Least-squares DLT on n >= 4 correspondences (Hartley normalisation, AᵀA from moment sums,
// h(2,2) fixed to 1 in normalised coordinates, 8x8 LDLT), used by the LO-RANSAC refits; `use`
// (may be null) selects the correspondences. Returns false when the fit is degenerate.
bool HomographyLeastSquares(const float* ref_x, const float* ref_y, const float* query_x, const float* query_y,
                            const uint8_t* use, int count, Eigen::Matrix3d* h);

// The homography as a RANSAC estimator (ransac.h). A model is the 3x3 matrix, row-major, scaled so
// its largest entry has magnitude 1; it is solved and scored in float. A sample is degenerate if
// three of its points are (nearly) collinear in either image or if it keeps the orientation of
// some point triplets but not of others (as OpenCV's checkSubset). The vector kernels are cloned
// for AVX2 with run-time dispatch, without FMA, so both clones give the same floats.
struct HomographyEstimator {
  static constexpr int kSampleSize = 4;
  static constexpr int kModelSize = 9;
  static constexpr float kNoModel[kModelSize] = {1, 0, 0, 0, 1, 0, 0, 0, 1};

  // The matches as structure of arrays, and as the (reference x, reference y, query x, query y)
  // quadruples that the sample kernels gather from.
  struct Data {
    const float *ref_x, *ref_y, *query_x, *query_y;
    const float* quads;
    int count;
  };
  // Data over the arrays (count entries each); *quads is scratch that holds the quadruples.
  static Data Prepare(const float* ref_x, const float* ref_y, const float* query_x, const float* query_y, int count,
                      std::vector<float>* quads);

  // Screening is the orientation test: most random samples fail it, and it is cheap.
  static void DrawAndScreen(const RansacSampler& sampler, uint32_t first_draw, const Data& data, SampleBatch* batch,
                            int32_t keep[kRansacLanes]);
  static void Solve(const SampleBatch& batch, const Data& data, ModelBatch<kModelSize>* out);
  // Division-free: |(u, v) / w - q| < t  <=>  |(u, v) - q w|² < t² w²  (false when w = 0).
  static int CountInliers(const float* model, const Data& data, float threshold_sq, int bar);
  static void MarkInliers(const float* model, const Data& data, float threshold_sq, uint8_t* mask);
  // HomographyLeastSquares on the masked matches, scaled as a model.
  static bool Refit(const Data& data, const uint8_t* mask, float* model);

  // The model as a matrix with H(2,2) = 1 (left as it is when H(2,2) is about 0).
  static Eigen::Matrix3d ToMatrix(const float* model);
};

}  // namespace hoilcd
