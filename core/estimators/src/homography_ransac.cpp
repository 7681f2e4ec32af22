#include "hoilcd/core/estimators/homography_ransac.h"

#include <algorithm>

#include "hoilcd/core/util/error.h"

namespace hoilcd {

int RansacHomographySoa(const float* ref_x, const float* ref_y, const float* query_x, const float* query_y, int count,
                        const RansacOptions& options, uint64_t seed, Eigen::Matrix3d* best_h, uint8_t* inlier_mask) {
  using E = HomographyEstimator;
  if (count < E::kSampleSize) {
    if (best_h != nullptr) best_h->setIdentity();
    if (inlier_mask != nullptr) std::fill(inlier_mask, inlier_mask + count, uint8_t{0});
    return 0;
  }
  std::vector<float> quads;
  const E::Data data = E::Prepare(ref_x, ref_y, query_x, query_y, count, &quads);
  float best[E::kModelSize];
  const int inliers = RunRansac<E>(data, options, seed, best);
  if (best_h != nullptr) *best_h = E::ToMatrix(best);
  if (inlier_mask != nullptr) {
    if (inliers == 0) {
      std::fill(inlier_mask, inlier_mask + count, uint8_t{0});
    } else {
      const float threshold_sq = static_cast<float>(options.inlier_threshold_px * options.inlier_threshold_px);
      E::MarkInliers(best, data, threshold_sq, inlier_mask);
    }
  }
  return inliers;
}

void RansacCounter::Count(const float* ref_x, const float* ref_y, const float* query_x, const float* query_y, int count,
                          const RansacOptions* variants, int num_variants, uint64_t seed, int* inliers,
                          int64_t* alone_ns, int64_t* total_ns) {
  const auto prepare = [&] { return HomographyEstimator::Prepare(ref_x, ref_y, query_x, query_y, count, &quads_); };
  variants_.Count(count, prepare, variants, num_variants, seed, inliers, alone_ns, total_ns);
}

namespace {

// Checks the options, gathers the matched coordinates as structure of arrays and runs
// RansacHomographySoa on them (best_h and inlier_mask as there).
int RansacOnMatches(const std::vector<Point2>& query, const std::vector<Point2>& reference,
                    const std::vector<Correspondence>& matches, const RansacOptions& options, uint64_t seed,
                    Eigen::Matrix3d* best_h, uint8_t* inlier_mask) {
  const std::string problem = options.Check();
  HOILCD_CHECK_MSG(problem.empty(), problem);
  const int count = static_cast<int>(matches.size());
  std::vector<float> xy(4 * static_cast<size_t>(count));  // reference x, reference y, query x, query y
  for (int i = 0; i < count; ++i) {
    const Correspondence& m = matches[i];
    HOILCD_CHECK_MSG(m.query >= 0 && m.query < static_cast<int>(query.size()) && m.reference >= 0 &&
                         m.reference < static_cast<int>(reference.size()),
                     "match " << i << " (" << m.query << ", " << m.reference << ") is out of range");
    xy[i] = reference[m.reference].x;
    xy[count + i] = reference[m.reference].y;
    xy[2 * count + i] = query[m.query].x;
    xy[3 * count + i] = query[m.query].y;
  }
  return RansacHomographySoa(xy.data(), xy.data() + count, xy.data() + 2 * count, xy.data() + 3 * count, count, options,
                             seed, best_h, inlier_mask);
}

}  // namespace

HomographyResult EstimateHomographyRansac(const std::vector<Point2>& query, const std::vector<Point2>& reference,
                                          const std::vector<Correspondence>& matches, const RansacOptions& options,
                                          uint64_t seed) {
  HomographyResult result;
  result.inlier_mask.resize(matches.size());
  result.inliers =
      RansacOnMatches(query, reference, matches, options, seed, &result.reference_to_query, result.inlier_mask.data());
  return result;
}

int CountRansacInliers(const std::vector<Point2>& query, const std::vector<Point2>& reference,
                       const std::vector<Correspondence>& matches, const RansacOptions& options, uint64_t seed) {
  return RansacOnMatches(query, reference, matches, options, seed, nullptr, nullptr);
}

}  // namespace hoilcd
