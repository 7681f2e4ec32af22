// Trajectory error as evo (github.com/MichaelGrupp/evo) and the TUM benchmark define it: ATE is the
// RMSE of position differences after the SE(2) Umeyama alignment (rotation + translation, no scale)
// of the estimate to the reference; RPE is the RMSE of the translation part of
// (ref_i⁻¹ ref_j)⁻¹ (est_i⁻¹ est_j) over pairs i → j a fixed distance apart along the reference.
#pragma once

#include <vector>

#include "hoilcd/bench/slam/pose_graph.h"

namespace hoilcd {

// estimate → reference alignment: reference ≈ R(angle) · estimate + t.
struct Alignment2d {
  double angle_rad = 0;
  double tx_m = 0, ty_m = 0;
  Pose2d Apply(const Pose2d& p) const;
};

// Least-squares rigid alignment of the positions (Umeyama 1991, via Eigen::umeyama without scale).
// HOILCD_CHECK: same length, at least 2 poses.
Alignment2d UmeyamaAlign(const std::vector<Pose2d>& estimate, const std::vector<Pose2d>& reference);

// ATE RMSE in metres after UmeyamaAlign.
double AteRmseM(const std::vector<Pose2d>& estimate, const std::vector<Pose2d>& reference);

// RPE RMSE (translation, metres) over pairs chosen as evo does with --delta D --delta_unit m
// (all_pairs off): from i, j is the first pose whose path length along the reference from i is
// ≥ delta_m, then i = j. 0 pairs (path shorter than delta): returns 0 and sets *pairs = 0.
// `segment` (empty, or one value per pose): pairs never span two segments (recording runs, whose
// poses are not joined by a path); the pairing starts again at each segment's first pose.
double RpeRmseM(const std::vector<Pose2d>& estimate, const std::vector<Pose2d>& reference, double delta_m,
                int* pairs = nullptr, const std::vector<int>& segment = {});

}  // namespace hoilcd
