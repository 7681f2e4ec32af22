// Random homographies and matched point sets with known inliers, for the homography model's and
// its RANSAC's tests: a 256 x 192 image, reference point i matched to query point i.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "hoilcd/core/estimators/homography_ransac.h"
#include "hoilcd/core/util/random.h"

namespace hoilcd {

constexpr float kWidthPx = 256, kHeightPx = 192;

// A plausible reference -> query homography: scale/shear near 1, shift, mild perspective.
inline Eigen::Matrix3d RandomHomography(Rng& rng) {
  Eigen::Matrix3d h;
  h << rng.Uniform(0.8, 1.2), rng.Uniform(-0.15, 0.15), rng.Uniform(-25, 25), rng.Uniform(-0.15, 0.15),
      rng.Uniform(0.8, 1.2), rng.Uniform(-20, 20), rng.Uniform(-6e-4, 6e-4), rng.Uniform(-6e-4, 6e-4), 1.0;
  return h;
}

inline Point2 Apply(const Eigen::Matrix3d& h, Point2 p) {
  const Eigen::Vector3d q = h * Eigen::Vector3d(p.x, p.y, 1.0);
  return Point2(static_cast<float>(q.x() / q.z()), static_cast<float>(q.y() / q.z()));
}

inline Point2 RandomPoint(Rng& rng) {
  return Point2(static_cast<float>(rng.Uniform(0, kWidthPx)), static_cast<float>(rng.Uniform(0, kHeightPx)));
}

// Matches 0..n-1 pair reference[i] with query[i]; the first `num_inliers` follow h plus Gaussian
// noise of noise_px per axis, the rest are uniform outliers.
struct HomographyProblem {
  std::vector<Point2> query, reference;
  std::vector<Correspondence> matches;
  int num_inliers = 0;
  Eigen::Matrix3d reference_to_query;  // the inliers' homography
};

inline HomographyProblem MakeHomographyProblem(Rng& rng, int n, int num_inliers, double noise_px) {
  HomographyProblem p;
  const Eigen::Matrix3d h = RandomHomography(rng);
  p.num_inliers = num_inliers;
  p.reference_to_query = h;
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

}  // namespace hoilcd
