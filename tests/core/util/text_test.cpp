#include "hoilcd/core/util/text.h"

#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

namespace hoilcd {
namespace {

TEST(Fixed, PrintsTheAskedDecimalsAndADashForAMissingFigure) {
  EXPECT_EQ(Fixed(0.12345), "0.123");
  EXPECT_EQ(Fixed(2.5, 0), "2");  // round half to even, as printf
  EXPECT_EQ(Fixed(-1.0, 2), "-1.00");
  EXPECT_EQ(Fixed(NAN), "-");
  EXPECT_EQ(Fixed(std::numeric_limits<double>::infinity()), "-");
}

TEST(ShortestDouble, ReadsBackAsExactlyTheSameDouble) {
  for (const double v : {0.1, 1.0 / 3.0, -2.5e-300, 6.02214076e23, 123456789.0}) {
    EXPECT_EQ(std::stod(ShortestDouble(v)), v);
  }
  EXPECT_EQ(ShortestDouble(0.1), "0.1");
  EXPECT_EQ(ShortestDouble(3.0), "3");
}

TEST(CsvNumber, IsEmptyForAMissingFigureAndRoundsToSignificantDigitsWhenAsked) {
  EXPECT_EQ(CsvNumber(NAN), "");
  EXPECT_EQ(CsvNumber(-std::numeric_limits<double>::infinity(), 6), "");
  EXPECT_EQ(CsvNumber(1.0 / 3.0), ShortestDouble(1.0 / 3.0));
  EXPECT_EQ(CsvNumber(1.0 / 3.0, 6), "0.333333");
}

}  // namespace
}  // namespace hoilcd
