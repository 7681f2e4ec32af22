#include "hoilcd/core/util/stats.h"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

namespace hoilcd {
namespace {

TEST(Median, IsTheMiddleValueOrTheMeanOfTheTwoMiddleValues) {
  EXPECT_DOUBLE_EQ(Median({3.0, 1.0, 2.0}), 2.0);
  EXPECT_DOUBLE_EQ(Median({4.0, 1.0, 3.0, 2.0}), 2.5);
  EXPECT_DOUBLE_EQ(Median({7.0}), 7.0);
  EXPECT_TRUE(std::isnan(Median({})));
}

TEST(Median, AgreesWithTheHalfQuantile) {
  const std::vector<double> values = {0.3, 9.1, -2.0, 4.4, 4.4, 12.5};
  EXPECT_NEAR(Median(values), Quantile(values, 0.5), 1e-12);
}

TEST(Quantile, InterpolatesLinearlyBetweenOrderStatistics) {
  const std::vector<double> values = {10.0, 0.0, 20.0, 30.0};
  EXPECT_DOUBLE_EQ(Quantile(values, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(Quantile(values, 1.0), 30.0);
  EXPECT_DOUBLE_EQ(Quantile(values, 0.9), 27.0);  // at 2.7: 20 + 0.7 * 10
  EXPECT_TRUE(std::isnan(Quantile({}, 0.5)));
  EXPECT_THROW(Quantile(values, 1.5), std::logic_error);
}

TEST(MeanAndStdDev, UseTheSampleStandardDeviationAndAreNaNForNoValues) {
  EXPECT_DOUBLE_EQ(Mean({1.0, 2.0, 6.0}), 3.0);
  EXPECT_DOUBLE_EQ(StdDev({1.0, 2.0, 6.0}), std::sqrt(7.0));  // (4 + 1 + 9) / 2
  EXPECT_DOUBLE_EQ(StdDev({5.0}), 0.0);
  EXPECT_TRUE(std::isnan(Mean({})));
  EXPECT_TRUE(std::isnan(StdDev({})));
}

}  // namespace
}  // namespace hoilcd
