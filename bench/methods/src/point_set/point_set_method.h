// Shared by the point-set methods (SLCD, DLCD, their -lo variants and oracles): every query against its own
// database through a front end's RetrievalIndex (MNN -> vertical filter -> RANSAC inliers), timed
// per query. Point-set methods on the same index with the same matching options share one pass:
// each pair's MNN is found once, then every method's RANSAC runs on it.
#pragma once

#include <string>

#include "hoilcd/bench/methods/loop_closure_method.h"
#include "hoilcd/core/matching/matching.h"
#include "hoilcd/core/optim/ransac.h"
#include "hoilcd/core/place_recognition/retrieval_index.h"

namespace hoilcd {

// The point-set methods' own options (--param slcd.ransac_trials=50, slcd-lo.lo_refits=3, ...).
// Defaults and ranges are MatchOptions' and RansacOptions' own; the table says which fields a
// method exposes.
struct PointSetOptions {
  MatchOptions match;    // vertical_tolerance; image_height_px is the dataset's, set when scoring
  RansacOptions ransac;  // trials, inlier_threshold_px; local_optimisation_refits (-lo variants)

  // The fields a method exposes: with `lo`, also lo_refits (default 2 refits).
  static const OptionTable<PointSetOptions>& Table(bool lo);
};

class PointSetMethod : public LoopClosureMethod {
 public:
  // front_end: kKeypoints (corner keypoints), kPersons (HOI points) or an oracle's
  // (kIdealKeypoints, kTruePersons); lo: LO-RANSAC refits (the -lo variants, PointSetOptions' lo_refits).
  PointSetMethod(FrontEnd front_end, bool lo) : front_end_(front_end), lo_(lo) {}

  ShownFeatures Features() const override;
  std::set<FrontEnd> FrontEnds() const override { return {front_end_}; }
  bool Online() const override { return true; }
  std::unique_ptr<MethodOptions> Options() const override;
  MethodScores Score(const MethodContext& context) const override;
  std::optional<PairMatches> MatchPair(const PairMatchInput& input) const override;
  std::string PassKey(const MethodContext& context) const override;
  std::vector<MethodScores> ScoreTogether(const std::vector<const LoopClosureMethod*>& methods,
                                          const std::vector<MethodContext>& contexts) const override;

 private:
  FrontEnd front_end_;
  bool lo_;
};

}  // namespace hoilcd
