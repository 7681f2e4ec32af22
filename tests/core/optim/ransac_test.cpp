#include "hoilcd/core/optim/ransac.h"

#include <gtest/gtest.h>

#include "option_properties.h"

namespace hoilcd {
namespace {

TEST(RansacOptions, HoldsThePapersDefaultsFromItsTableAndChecksEveryBound) {
  const RansacOptions options;
  EXPECT_EQ(options.trials, 100);  // paper, section 5.2
  EXPECT_EQ(options.inlier_threshold_px, 5.0);
  EXPECT_EQ(options.local_optimisation_refits, 0);
  ExpectConstructedHoldsTheTableDefaults<RansacOptions>();
  EXPECT_EQ(ExpectEveryBoundCrossedIsNamedByCheck<RansacOptions>(), 4);
}

}  // namespace
}  // namespace hoilcd
