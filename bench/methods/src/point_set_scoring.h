// Shared by the point-set methods (SLCD, DLCD and their -lo variants): every query against its own
// database through a front end's RetrievalIndex (MNN -> vertical filter -> RANSAC inliers), timed
// per query. Point-set methods on the same index with the same matching options share one pass:
// each pair's MNN is found once, then every method's RANSAC runs on it.
#pragma once

#include <string>

#include "hoilcd/bench/methods/loop_closure_method.h"
#include "hoilcd/core/optim/ransac.h"
#include "hoilcd/core/place_recognition/retrieval_index.h"

namespace hoilcd {

class PointSetMethod : public LoopClosureMethod {
 public:
  // front_end: kKeypoints (corner keypoints) or kPersons (HOI points); lo: LO-RANSAC refits
  // (the -lo variants, BenchOptions::lo_refits).
  PointSetMethod(FrontEnd front_end, bool lo) : front_end_(front_end), lo_(lo) {}

  ShownFeatures Features() const override;
  std::set<FrontEnd> FrontEnds() const override { return {front_end_}; }
  const OptionTable<BenchOptions>* Params() const override;
  MethodScores Score(const MethodContext& context) const override;
  std::string PassKey(const MethodContext& context) const override;
  std::vector<MethodScores> ScoreTogether(const std::vector<const LoopClosureMethod*>& methods,
                                          const std::vector<MethodContext>& contexts) const override;

 private:
  RansacOptions Ransac(const BenchOptions& options) const;

  FrontEnd front_end_;
  bool lo_;
};

}  // namespace hoilcd
