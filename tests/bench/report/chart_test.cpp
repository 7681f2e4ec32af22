#include "hoilcd/bench/report/chart.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "option_properties.h"

namespace hoilcd {
namespace {

const cv::Scalar kMagenta(255, 0, 255);  // not in the palette, not a grey
const double kNaN = std::numeric_limits<double>::quiet_NaN();

Series MakeSeries(std::string label, std::vector<double> x, std::vector<double> y) {
  Series s;
  s.label = std::move(label);
  s.x = std::move(x);
  s.y = std::move(y);
  return s;
}

// Pixels of exactly `colour` inside / outside `area`.
std::pair<int, int> CountColour(const cv::Mat& image, const cv::Scalar& colour, cv::Rect area) {
  cv::Mat mask;
  cv::inRange(image, colour, colour, mask);
  const int inside = cv::countNonZero(mask(area & cv::Rect(0, 0, image.cols, image.rows)));
  return {inside, cv::countNonZero(mask) - inside};
}

void ExpectNiceTicks(double lo, double hi, int max_count) {
  SCOPED_TRACE(::testing::Message() << "[" << lo << ", " << hi << "] max " << max_count);
  const std::vector<double> ticks = NiceTicks(lo, hi, max_count);
  ASSERT_GE(ticks.size(), 2u);
  if (max_count >= 5) {
    ASSERT_LE(ticks.size(), static_cast<std::size_t>(max_count));
  }
  const double step = ticks[1] - ticks[0];
  const double mantissa = step / std::pow(10.0, std::floor(std::log10(step) + 1e-9));
  EXPECT_TRUE(std::abs(mantissa - 1) < 1e-6 || std::abs(mantissa - 2) < 1e-6 || std::abs(mantissa - 5) < 1e-6)
      << "step " << step;
  for (std::size_t i = 0; i < ticks.size(); ++i) {
    EXPECT_GE(ticks[i], lo - 1e-9 * step);
    EXPECT_LE(ticks[i], hi + 1e-9 * step);
    EXPECT_NEAR(std::remainder(ticks[i], step), 0.0, 1e-9 * step) << "tick not a multiple of step";
    if (i > 0) {
      EXPECT_NEAR(ticks[i] - ticks[i - 1], step, 1e-9 * step);
    }
  }
  // A finer 1-2-5 step (at most 2.5 times finer) would have given more than max_count ticks.
  if (ticks.size() <= static_cast<std::size_t>(max_count)) {
    EXPECT_GT(2.5 * (hi - lo) / step + 1.0, max_count);
  }
}

TEST(PaletteColour, TwelveSeriesGetClearlyDifferentColoursBeforeOneRepeats) {
  // hoilcd bench plots nine methods in one chart; with eight colours the ninth took the first's.
  for (size_t i = 0; i < 12; ++i) {
    for (size_t j = i + 1; j < 12; ++j) {
      EXPECT_GT(cv::norm(PaletteColour(i) - PaletteColour(j)), 60.0) << i << " vs " << j;
    }
  }
  EXPECT_EQ(PaletteColour(12), PaletteColour(0));
}

TEST(NiceTicks, ZeroToOneGivesFifths) {
  const std::vector<double> ticks = NiceTicks(0.0, 1.0, 6);
  const std::vector<double> expected = {0.0, 0.2, 0.4, 0.6, 0.8, 1.0};
  ASSERT_EQ(ticks.size(), expected.size());
  for (std::size_t i = 0; i < ticks.size(); ++i) EXPECT_NEAR(ticks[i], expected[i], 1e-12);
  EXPECT_EQ(NiceTicks(0.0, 1.0, 11).size(), 11u);  // tenths
  EXPECT_EQ(NiceTicks(0.13, 0.87, 3).size(), 4u);  // 0.5 alone would be one tick: 0.2 apart
}

TEST(NiceTicks, AwkwardRangesGetOneTwoFiveStepsInsideTheRange) {
  for (const int max_count : {3, 5, 8, 10}) {
    ExpectNiceTicks(0.0, 1.0, max_count);
    ExpectNiceTicks(0.13, 0.87, max_count);
    ExpectNiceTicks(-3.0, 1250.0, max_count);
    ExpectNiceTicks(-0.004, 0.0031, max_count);
    ExpectNiceTicks(1e6, 1e6 + 3.0, max_count);
  }
  const std::vector<double> thousands = NiceTicks(-3.0, 1250.0, 8);
  ASSERT_EQ(thousands.size(), 7u);
  EXPECT_DOUBLE_EQ(thousands.front(), 0.0);
  EXPECT_DOUBLE_EQ(thousands.back(), 1200.0);
  const std::vector<double> inner = NiceTicks(0.13, 0.87, 8);
  ASSERT_EQ(inner.size(), 7u);
  EXPECT_NEAR(inner.front(), 0.2, 1e-12);
  EXPECT_NEAR(inner.back(), 0.8, 1e-12);
}

TEST(NiceTicks, DegenerateAndNonFiniteRangesGiveAtMostOneTick) {
  EXPECT_EQ(NiceTicks(2.5, 2.5, 6), std::vector<double>{2.5});
  EXPECT_TRUE(NiceTicks(kNaN, 1.0, 6).empty());
  EXPECT_TRUE(NiceTicks(0.0, std::numeric_limits<double>::infinity(), 6).empty());
  EXPECT_TRUE(NiceTicks(1.0, 0.0, 6).empty());
  EXPECT_THROW(NiceTicks(0.0, 1.0, 1), std::logic_error);
}

TEST(PlotOptions, CheckRejectsBadSizesRangesAndFonts) {
  EXPECT_EQ(PlotOptions{}.Check(), "");
  PlotOptions o;
  o.width_px = 0;
  EXPECT_NE(o.Check().find("width_px"), std::string::npos);
  o = PlotOptions{};
  o.height_px = -5;
  EXPECT_NE(o.Check().find("height_px"), std::string::npos);
  o = PlotOptions{};
  o.x_range = std::make_pair(1.0, 1.0);
  EXPECT_NE(o.Check().find("x_range"), std::string::npos);
  o = PlotOptions{};
  o.y_range = std::make_pair(0.0, kNaN);
  EXPECT_NE(o.Check().find("y_range"), std::string::npos);
  o = PlotOptions{};
  o.font_scale = 0.1;
  EXPECT_NE(o.Check().find("font_scale"), std::string::npos);
  o = PlotOptions{};
  o.width_px = 0;
  EXPECT_THROW(LinePlot({}, o), std::logic_error);
}

TEST(PlotOptions, HoldTheirTablesDefaultsUnsetRangesAndEveryBoundIsChecked) {
  EXPECT_FALSE(PlotOptions().x_range.has_value());
  EXPECT_FALSE(PlotOptions().y_range.has_value());
  ExpectConstructedHoldsTheTableDefaults<PlotOptions>();
  EXPECT_EQ(ExpectEveryBoundCrossedIsNamedByCheck<PlotOptions>(), 6);
}

TEST(LinePlot, HasRequestedSizeAndThreeChannels) {
  for (const cv::Size size : {cv::Size(800, 560), cv::Size(333, 201), cv::Size(1600, 900)}) {
    PlotOptions o;
    o.width_px = size.width;
    o.height_px = size.height;
    o.title = "Precision-recall";
    o.x_label = "recall";
    o.y_label = "precision";
    Series s = MakeSeries("DLCD", {0.0, 0.5, 1.0}, {1.0, 0.8, 0.3});
    const cv::Mat image = LinePlot({s}, o);
    EXPECT_EQ(image.size(), size);
    EXPECT_EQ(image.type(), CV_8UC3);
  }
}

TEST(LinePlot, SeriesColourAppearsInsideThePlotAreaAndNowhereElse) {
  PlotOptions o;
  o.x_range = std::make_pair(0.0, 1.0);
  o.y_range = std::make_pair(0.0, 1.0);
  Series s = MakeSeries("clipped", {-1.0, 0.5, 2.0, 0.5}, {0.5, 0.5, 3.0, -1e30});
  s.colour = kMagenta;
  s.markers = true;
  cv::Rect area;
  const cv::Mat image = LinePlot({s}, o, &area);
  ASSERT_GT(area.area(), 0);
  EXPECT_TRUE((area & cv::Rect(0, 0, image.cols, image.rows)) == area);
  const auto [inside, outside] = CountColour(image, kMagenta, area);
  EXPECT_GT(inside, 200);
  EXPECT_EQ(outside, 0);
}

TEST(LinePlot, NaNEmptyAndConstantSeriesGiveValidImages) {
  Series empty = MakeSeries("empty", {}, {});
  Series all_nan = MakeSeries("nan", {kNaN, kNaN}, {kNaN, kNaN});
  Series gap = MakeSeries("gap", {0.0, 1.0, 2.0, 3.0, 4.0}, {1.0, 2.0, kNaN, 2.0, 1.0});
  gap.colour = kMagenta;
  gap.y_low = {0.5, kNaN, kNaN, 1.5, 0.5};
  gap.y_high = {1.5, 2.5, kNaN, 2.5, 1.5};
  Series constant = MakeSeries("constant", {0.0, 1.0, 2.0}, {0.7, 0.7, 0.7});
  constant.colour = cv::Scalar(0, 200, 0);
  Series infinite = MakeSeries("inf", {0.0, 1.0}, {std::numeric_limits<double>::infinity(), 1.0});
  PlotOptions o;
  for (const std::vector<Series>& set :
       {std::vector<Series>{}, std::vector<Series>{empty}, std::vector<Series>{all_nan},
        std::vector<Series>{empty, all_nan, gap, infinite}, std::vector<Series>{constant}}) {
    const cv::Mat image = LinePlot(set, o);
    EXPECT_EQ(image.size(), cv::Size(o.width_px, o.height_px));
    EXPECT_EQ(image.type(), CV_8UC3);
  }
  EXPECT_GT(CountColour(LinePlot({gap}, o), kMagenta, {0, 0, 800, 560}).first, 100);
  EXPECT_GT(CountColour(LinePlot({constant}, o), cv::Scalar(0, 200, 0), {0, 0, 800, 560}).first, 100);
  gap.band = true;
  EXPECT_EQ(LinePlot({gap}, o).type(), CV_8UC3);
}

TEST(LinePlot, MismatchedSeriesSizesAreRejected) {
  EXPECT_THROW(LinePlot({MakeSeries("bad", {0.0, 1.0}, {0.0})}, PlotOptions{}), std::logic_error);
  Series spread = MakeSeries("bad spread", {0.0, 1.0}, {0.0, 1.0});
  spread.y_low = {0.0, 0.5};
  EXPECT_THROW(LinePlot({spread}, PlotOptions{}), std::logic_error);
}

TEST(LinePlot, LegendDoesNotHideDataWhenACornerIsFree) {
  // Data only in the upper right: the legend must go elsewhere and leave every data pixel shown.
  Series s = MakeSeries("upper right", {0.6, 0.8, 1.0}, {0.6, 1.0, 0.8});
  s.colour = kMagenta;
  s.markers = true;
  PlotOptions o;
  o.x_range = std::make_pair(0.0, 1.0);
  o.y_range = std::make_pair(0.0, 1.0);
  o.legend = false;
  cv::Mat without;
  cv::inRange(LinePlot({s}, o), kMagenta, kMagenta, without);
  o.legend = true;
  cv::Mat with_legend;
  cv::inRange(LinePlot({s}, o), kMagenta, kMagenta, with_legend);
  EXPECT_GT(cv::countNonZero(without), 100);
  cv::Mat hidden;
  cv::bitwise_and(without, ~with_legend, hidden);
  EXPECT_EQ(cv::countNonZero(hidden), 0);
}

TEST(BarPlot, BarsAreDrawnInsideThePlotAreaWithTheRequestedSize) {
  Series a = MakeSeries("SLCD", {}, {0.4, 0.5, 0.45});
  a.colour = kMagenta;
  a.y_low = {0.35, 0.45, 0.4};
  a.y_high = {0.45, 0.55, 0.5};
  Series b = MakeSeries("DLCD", {}, {0.7, kNaN, -0.1});
  PlotOptions o;
  o.width_px = 640;
  o.height_px = 400;
  cv::Rect area;
  const cv::Mat image = BarPlot({"lap 1", "lap 2", "lap 3"}, {a, b}, o, &area);
  EXPECT_EQ(image.size(), cv::Size(640, 400));
  EXPECT_EQ(image.type(), CV_8UC3);
  const auto [inside, outside] = CountColour(image, kMagenta, area);
  EXPECT_GT(inside, 1000);
  EXPECT_EQ(outside, 0);
  EXPECT_THROW(BarPlot({"one"}, {a}, o), std::logic_error);
}

}  // namespace
}  // namespace hoilcd
