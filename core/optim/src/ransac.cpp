#include "hoilcd/core/optim/ransac.h"

namespace hoilcd {

RansacOptions::RansacOptions() { Table().FillDefaults(this); }

const OptionTable<RansacOptions>& RansacOptions::Table() {
  using O = RansacOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("trials", &O::trials, 100, "", R::Closed(1, kRansacMaxTrials), "RANSAC hypotheses per pair (paper: 100)")
          .Add("redraw_degenerate_samples", &O::redraw_degenerate_samples, true,
               "a degenerate sample is redrawn (up to 10 draws per trial on average) instead of using up its trial")
          .Add("inlier_threshold_px", &O::inlier_threshold_px, 5.0, "px", R::Any().Above(0),
               "reprojection error bound of an inlier")
          // Each refit is a least-squares solve per better hypothesis; LO-RANSAC uses a few.
          .Add("local_optimisation_refits", &O::local_optimisation_refits, 0, "", R::Closed(0, 100),
               "LO-RANSAC least-squares refits on the inliers of each new best model (0: plain RANSAC, the paper's)");
  return table;
}

std::string RansacOptions::Check() const { return Table().FirstProblem(*this); }

}  // namespace hoilcd
