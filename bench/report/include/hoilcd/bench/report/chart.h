// A chart toolkit drawn with OpenCV into 8-bit BGR images: line plots (PR curves, metric vs
// swept parameter with spread over seeds) and grouped bar plots over numeric axes with 1-2-5
// ticks, a grid and a legend; plus, in namespace chart, the axes and drawing building blocks
// that the domain figures (figures.h) draw with.
#pragma once

#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

// Colour i of the colour-blind-safe Okabe-Ito palette as BGR (blue, vermillion, bluish green,
// orange, reddish purple, sky blue, black, yellow), cycling.
cv::Scalar PaletteColour(std::size_t index);

// Tick values k * step inside [lo, hi], where step is 1, 2 or 5 times a power of ten: the
// smallest such step giving at most max_count ticks (max_count >= 2), or the largest giving two
// when that gives only one (possible for max_count < 5). Empty if lo > hi or not finite.
std::vector<double> NiceTicks(double lo, double hi, int max_count);

// One data series. NaN in x or y leaves a gap in the line; a NaN bound leaves out that error bar.
struct Series {
  std::string label;                 // legend text; empty keeps the series out of the legend
  std::vector<double> x;             // abscissae (LinePlot); ignored by BarPlot
  std::vector<double> y;             // ordinates, same size as x (LinePlot) or one per group (BarPlot)
  std::vector<double> y_low;         // lower end of the spread per point (empty: no spread)
  std::vector<double> y_high;        // upper end of the spread per point (empty: no spread)
  std::optional<cv::Scalar> colour;  // BGR; unset: PaletteColour(position in the series list)
  bool line = true;                  // join consecutive points with a line
  bool markers = false;              // draw a marker at each point, shape distinct per series
  bool band = false;                 // draw the spread as a shaded band instead of error bars
};

// Defaults and ranges: Table() in chart.cpp.
struct PlotOptions {
  std::string title;    // drawn above the axes; empty: none
  std::string x_label;  // below the x axis; empty: none
  std::string y_label;  // left of the y axis, rotated; empty: none
  int width_px;         // image width, pixels
  int height_px;        // image height, pixels
  // Shown x and y intervals, data units; unset (as constructed): fit the data. Not table fields
  // (a table holds no pairs); its rules check them.
  std::optional<std::pair<double, double>> x_range;
  std::optional<std::pair<double, double>> y_range;
  bool equal_aspect;  // one data unit is as long on both axes (ranges are widened to fit)
  bool legend;        // draw a legend of labelled series, in the corner hiding least data
  double font_scale;  // tick-label size (OpenCV Hershey scale); labels and title are larger

  PlotOptions();  // the registered defaults
  // Every field once: name, default, unit, range, description.
  static const OptionTable<PlotOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

// Series as lines and/or markers over numeric axes with 1-2-5 ticks, a light grid and a legend.
// plot_area_px, when given, receives the axes box in image pixels (data is clipped to it).
cv::Mat LinePlot(const std::vector<Series>& series, const PlotOptions& options, cv::Rect* plot_area_px = nullptr);

// Grouped bars: one group per name along x, one bar per series inside each group (series.y
// holds one value per group, y_low/y_high optional error bars). The y axis always includes 0.
cv::Mat BarPlot(const std::vector<std::string>& groups, const std::vector<Series>& series, const PlotOptions& options,
                cv::Rect* plot_area_px = nullptr);

namespace chart {

constexpr int kShift = 4;  // fixed-point fraction bits for sub-pixel drawing
constexpr double kSubPixels = 1 << kShift;

// Closed data interval; starts empty and grows with Add.
struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void Add(double v) {
    if (!std::isfinite(v)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  double Span() const { return hi - lo; }
};

// Axes: where the data intervals land in the image, and the ticks along them.
struct Axes {
  cv::Rect frame;         // axes box, image pixels
  Range x, y;             // shown data intervals
  double inset_px = 0.0;  // the intervals map to the frame shrunk by this on every side
  std::vector<double> x_ticks, y_ticks;
  std::vector<std::string> x_tick_labels, y_tick_labels;
  int y_tick_labels_width_px = 0;

  // Pixel position inside the frame (frame-local, sub-pixel).
  cv::Point2d ToLocal(double xv, double yv) const {
    const double w = frame.width - 1 - 2 * inset_px;
    const double h = frame.height - 1 - 2 * inset_px;
    return {inset_px + (xv - x.lo) / x.Span() * w, frame.height - 1 - inset_px - (yv - y.lo) / y.Span() * h};
  }
};

struct AxesSpec {
  Range x, y;                           // drawable data intervals
  std::vector<std::string> categories;  // if set: x ticks at 0..n-1 with these labels
  double inset_px = 8.0;                // see Axes::inset_px
  bool equal_aspect = false;
};

struct LegendItem {
  std::string label;
  cv::Scalar colour;
  bool line = false;    // a short line sample
  int marker = -1;      // marker shape, -1: none
  bool swatch = false;  // a filled box (bars)
};

using DrawData = std::function<void(cv::Mat& frame_roi, const Axes& axes)>;

cv::Scalar Grey(int level);  // BGR grey of that level, 0..255
cv::Scalar White();

// `option` as an interval if set, else `data` made drawable ([0, 1] when empty, widened around a
// single value).
Range FromOption(const std::optional<std::pair<double, double>>& option, Range data);

// Size of `text` in the chart font (OpenCV Hershey simplex) at `scale`.
cv::Size TextSize(const std::string& text, double scale);

// Text whose box (cap height, no descender) is placed so that the point at fractions
// (h_align, v_align) of it lands on anchor: (0, 0) top-left, (0.5, 0.5) centre, (1, 1) bottom-right.
void PutText(cv::Mat& image, const std::string& text, cv::Point2d anchor, double h_align, double v_align, double scale,
             const cv::Scalar& colour);

cv::Point SubPixel(cv::Point2d p);  // fixed point with kShift fraction bits, far inside int range
cv::Point Pixel(cv::Point2d p);     // nearest whole pixel, far inside int range
bool Finite(cv::Point2d p);

// Anti-aliased segment clipped to the image first, so points far outside the range draw right.
void Segment(cv::Mat& image, cv::Point2d a, cv::Point2d b, const cv::Scalar& colour, int thickness);

// Draws a chart: grid, `draw_data` inside the axes frame, the frame with ticks and labels, the
// legend in the place hiding least data (when the legend would hide data, the y range is
// automatic and the legend small, it draws again with room for the legend at the top).
// plot_area_px, when given, receives the axes box in image pixels.
cv::Mat Render(const PlotOptions& o, AxesSpec spec, bool vertical_grid, const std::vector<LegendItem>& legend,
               const DrawData& draw_data, cv::Rect* plot_area_px);

}  // namespace chart

}  // namespace hoilcd
