// Domain figures of the report, drawn on the chart toolkit (chart.h): the robot trajectory seen
// from above with obstacles and retrieval links, and thermal match mosaics like the paper's
// figures 6 and 7.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "hoilcd/bench/report/chart.h"
#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

struct TrajectoryPoint {
  double x_m = 0.0;                  // robot position in the world, metres
  double y_m = 0.0;                  // robot position in the world, metres
  cv::Scalar colour{128, 128, 128};  // BGR, e.g. by whether the frame's top-1 is correct
};

struct TrajectoryLink {
  cv::Point2d from_m;                // query position, metres
  cv::Point2d to_m;                  // retrieved reference position, metres
  cv::Scalar colour{128, 128, 128};  // BGR
};

struct LegendEntry {
  std::string label;  // legend text
  cv::Scalar colour;  // BGR of the dot shown next to it
};

// Top view of the trajectory, always with equal aspect (options.equal_aspect is implied):
// obstacle footprints (the dataset's footprints.json) as grey oriented rectangles and circles, the
// positions as coloured dots, then the links as thin half-transparent lines.
cv::Mat TrajectoryPlot(const std::vector<TrajectoryPoint>& points, const std::vector<TrajectoryLink>& links,
                       const std::vector<FootprintRecord>& footprints, const std::vector<LegendEntry>& legend,
                       const PlotOptions& options, cv::Rect* plot_area_px = nullptr);

// One picture in a match mosaic. Single-channel images are shown with the inferno colour map
// (8-bit as is, other depths stretched from their minimum to their maximum); BGR as is. An empty
// image gives a grey tile as large as the largest tile of its row (e.g. "no true match").
struct MatchTile {
  cv::Mat image;                       // CV_8UC1, CV_8UC3, or single-channel of any depth
  std::string caption;                 // drawn in the tile's top-left corner; empty: none
  std::vector<cv::Point2f> points;     // feature points, pixels of `image`
  cv::Scalar point_colour{0, 255, 0};  // BGR of the feature points
};

// Defaults and ranges: Table() in figures.cpp.
struct MosaicOptions {
  int scale;          // upscaling factor per tile (nearest neighbour), >= 1
  int gap_px;         // white gap between tiles and between rows, pixels
  double font_scale;  // caption size (OpenCV Hershey scale)

  MosaicOptions();  // the registered defaults
  // Every field once: name, default, unit, range, description.
  static const OptionTable<MosaicOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

// Tiles row by row, left-aligned on a white background. Width is the widest row: the sum of its
// tile widths times scale plus gaps; height is the sum of each row's tallest tile times scale
// plus gaps.
cv::Mat MatchMosaic(const std::vector<std::vector<MatchTile>>& rows, const MosaicOptions& options = {});

}  // namespace hoilcd
