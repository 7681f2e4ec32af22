// Report pictures drawn with OpenCV into 8-bit BGR images and written as PNG: line plots (PR
// curves, metric vs swept parameter with spread over seeds), grouped bar plots, the robot
// trajectory with retrieval links, and thermal match mosaics like the paper's figures 6 and 7.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

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

struct PlotOptions {
  std::string title;    // drawn above the axes; empty: none
  std::string x_label;  // below the x axis; empty: none
  std::string y_label;  // left of the y axis, rotated; empty: none
  int width_px = 800;   // image width, pixels
  int height_px = 560;  // image height, pixels
  std::optional<std::pair<double, double>> x_range;  // shown x interval, data units; unset: fit data
  std::optional<std::pair<double, double>> y_range;  // shown y interval, data units; unset: fit data
  bool equal_aspect = false;  // one data unit is as long on both axes (ranges are widened to fit)
  bool legend = true;         // draw a legend of labelled series, in the corner hiding least data
  double font_scale = 0.5;    // tick-label size (OpenCV Hershey scale); labels and title are larger

  // "" if valid, else what is wrong.
  std::string Check() const;
};

// Series as lines and/or markers over numeric axes with 1-2-5 ticks, a light grid and a legend.
// plot_area_px, when given, receives the axes box in image pixels (data is clipped to it).
cv::Mat LinePlot(const std::vector<Series>& series, const PlotOptions& options,
                 cv::Rect* plot_area_px = nullptr);

// Grouped bars: one group per name along x, one bar per series inside each group (series.y
// holds one value per group, y_low/y_high optional error bars). The y axis always includes 0.
cv::Mat BarPlot(const std::vector<std::string>& groups, const std::vector<Series>& series,
                const PlotOptions& options, cv::Rect* plot_area_px = nullptr);

struct TrajectoryPoint {
  double x_m = 0.0;                     // robot position in the world, metres
  double y_m = 0.0;                     // robot position in the world, metres
  cv::Scalar colour{128, 128, 128};     // BGR, e.g. by whether the frame's top-1 is correct
};

struct TrajectoryLink {
  cv::Point2d from_m;                   // query position, metres
  cv::Point2d to_m;                     // retrieved reference position, metres
  cv::Scalar colour{128, 128, 128};     // BGR
};

struct LegendEntry {
  std::string label;  // legend text
  cv::Scalar colour;  // BGR of the dot shown next to it
};

// Top view of the trajectory, always with equal aspect (options.equal_aspect is implied):
// obstacles as grey boxes (x, y = lower-left corner in metres; width, height in metres), the
// positions as coloured dots, then the links as thin half-transparent lines.
cv::Mat TrajectoryPlot(const std::vector<TrajectoryPoint>& points,
                       const std::vector<TrajectoryLink>& links,
                       const std::vector<cv::Rect2d>& obstacles_m,
                       const std::vector<LegendEntry>& legend, const PlotOptions& options,
                       cv::Rect* plot_area_px = nullptr);

// One picture in a match mosaic. Single-channel images are shown with the inferno colour map
// (8-bit as is, other depths stretched from their minimum to their maximum); BGR as is. An empty
// image gives a grey tile as large as the largest tile of its row (e.g. "no true match").
struct MatchTile {
  cv::Mat image;                          // CV_8UC1, CV_8UC3, or single-channel of any depth
  std::string caption;                    // drawn in the tile's top-left corner; empty: none
  std::vector<cv::Point2f> points;        // feature points, pixels of `image`
  cv::Scalar point_colour{0, 255, 0};     // BGR of the feature points
};

struct MosaicOptions {
  int scale = 2;             // upscaling factor per tile (nearest neighbour), >= 1
  int gap_px = 4;            // white gap between tiles and between rows, pixels
  double font_scale = 0.5;   // caption size (OpenCV Hershey scale)

  // "" if valid, else what is wrong.
  std::string Check() const;
};

// Tiles row by row, left-aligned on a white background. Width is the widest row: the sum of its
// tile widths times scale plus gaps; height is the sum of each row's tallest tile times scale
// plus gaps.
cv::Mat MatchMosaic(const std::vector<std::vector<MatchTile>>& rows,
                    const MosaicOptions& options = {});

// Encodes `image` as PNG and writes it atomically (to "<path>.tmp", then renamed). Throws
// InputError naming `path` when it cannot be written.
void WritePng(const std::string& path, const cv::Mat& image);

}  // namespace hoilcd
