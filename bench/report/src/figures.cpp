#include "hoilcd/bench/report/figures.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "hoilcd/core/util/error.h"

namespace hoilcd {
namespace {

using namespace chart;  // axes, text and sub-pixel drawing shared with the charts

constexpr double kDotRadiusPx = 3.0;  // trajectory dots

cv::Mat ToColour(const cv::Mat& image) {
  HOILCD_CHECK_MSG(image.channels() == 1 || image.type() == CV_8UC3,
                   "match tile must be single-channel or CV_8UC3, got type " << image.type());
  if (image.channels() == 3) return image;
  cv::Mat gray = image;
  if (image.depth() != CV_8U) cv::normalize(image, gray, 0, 255, cv::NORM_MINMAX, CV_8U);
  cv::Mat colour;
  cv::applyColorMap(gray, colour, cv::COLORMAP_INFERNO);
  return colour;
}

cv::Mat RenderTile(const MatchTile& tile, cv::Size empty_size, const MosaicOptions& o) {
  cv::Mat shown;
  if (tile.image.empty()) {
    shown = cv::Mat(empty_size, CV_8UC3, Grey(200));
  } else {
    cv::resize(ToColour(tile.image), shown, cv::Size(), o.scale, o.scale, cv::INTER_NEAREST);
  }
  const double radius = std::max(2.5, 1.5 * o.scale);
  for (const cv::Point2f& p : tile.points) {
    const cv::Point2d centre((p.x + 0.5) * o.scale - 0.5, (p.y + 0.5) * o.scale - 0.5);
    cv::circle(shown, SubPixel(centre), cvRound(radius * kSubPixels), tile.point_colour, cv::FILLED, cv::LINE_AA,
               kShift);
  }
  if (!tile.caption.empty()) {
    // A caption wider than its tile is drawn smaller until it fits (5 px margin each side).
    double font_scale = o.font_scale;
    cv::Size text = TextSize(tile.caption, font_scale);
    while (text.width + 10 > shown.cols && font_scale > 0.2) {
      font_scale *= 0.9;
      text = TextSize(tile.caption, font_scale);
    }
    const cv::Rect box = cv::Rect(0, 0, text.width + 10, text.height + 10) & cv::Rect(0, 0, shown.cols, shown.rows);
    cv::Mat backing = shown(box);
    cv::addWeighted(backing, 0.4, cv::Mat(backing.size(), backing.type(), Grey(0)), 0.6, 0.0, backing);
    PutText(shown, tile.caption, {5.0, 5.0}, 0.0, 0.0, font_scale, White());
  }
  return shown;
}

// Each footprint as a convex polygon in metres: a rectangle's 4 corners, a circle's 32 points.
std::vector<std::vector<cv::Point2d>> FootprintOutlines(const std::vector<FootprintRecord>& footprints) {
  std::vector<std::vector<cv::Point2d>> out;
  for (const FootprintRecord& f : footprints) {
    std::vector<cv::Point2d> outline;
    const cv::Point2d c(f.centre_m[0], f.centre_m[1]);
    if (f.kind == "circle") {
      for (int i = 0; i < 32; ++i) {
        const double t = 2.0 * CV_PI * i / 32;
        outline.push_back(c + f.radius_m * cv::Point2d(std::cos(t), std::sin(t)));
      }
    } else {
      const double yaw = f.yaw_deg * CV_PI / 180.0;
      const cv::Point2d u(std::cos(yaw), std::sin(yaw)), v(-std::sin(yaw), std::cos(yaw));
      static constexpr int kCorners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
      for (const auto& corner : kCorners) {
        outline.push_back(c + corner[0] * f.half_size_m[0] * u + corner[1] * f.half_size_m[1] * v);
      }
    }
    out.push_back(std::move(outline));
  }
  return out;
}

}  // namespace

cv::Mat TrajectoryPlot(const std::vector<TrajectoryPoint>& points, const std::vector<TrajectoryLink>& links,
                       const std::vector<FootprintRecord>& footprints, const std::vector<LegendEntry>& legend,
                       const PlotOptions& options, cv::Rect* plot_area_px) {
  Range x, y;
  for (const TrajectoryPoint& p : points) {
    x.Add(p.x_m);
    y.Add(p.y_m);
  }
  for (const TrajectoryLink& l : links) {
    for (const cv::Point2d& p : {l.from_m, l.to_m}) {
      x.Add(p.x);
      y.Add(p.y);
    }
  }
  const std::vector<std::vector<cv::Point2d>> outlines = FootprintOutlines(footprints);
  for (const std::vector<cv::Point2d>& outline : outlines) {
    for (const cv::Point2d& p : outline) {
      x.Add(p.x);
      y.Add(p.y);
    }
  }
  std::vector<LegendItem> items;
  for (const LegendEntry& e : legend) items.push_back({e.label, e.colour, false, 0, false});
  AxesSpec spec;
  spec.x = FromOption(options.x_range, x);
  spec.y = FromOption(options.y_range, y);
  spec.equal_aspect = true;
  spec.inset_px = 10.0;
  const DrawData draw = [&](cv::Mat& roi, const Axes& a) {
    for (const std::vector<cv::Point2d>& outline : outlines) {
      std::vector<cv::Point> polygon;
      for (const cv::Point2d& p : outline) {
        const cv::Point2d local = a.ToLocal(p.x, p.y);
        if (Finite(local)) polygon.push_back(Pixel(local));
      }
      if (polygon.size() != outline.size()) continue;
      cv::fillConvexPoly(roi, polygon, Grey(218));
      cv::polylines(roi, std::vector<std::vector<cv::Point>>{polygon}, true, Grey(160), 1);
    }
    for (const TrajectoryPoint& p : points) {
      const cv::Point2d c = a.ToLocal(p.x_m, p.y_m);
      if (!Finite(c)) continue;
      cv::circle(roi, SubPixel(c), cvRound(kDotRadiusPx * kSubPixels), p.colour, cv::FILLED, cv::LINE_AA, kShift);
    }
    if (links.empty()) return;
    cv::Mat overlay = roi.clone();
    for (const TrajectoryLink& l : links) {
      Segment(overlay, a.ToLocal(l.from_m.x, l.from_m.y), a.ToLocal(l.to_m.x, l.to_m.y), l.colour, 1);
    }
    cv::addWeighted(overlay, 0.6, roi, 0.4, 0.0, roi);
  };
  PlotOptions equal = options;
  equal.equal_aspect = true;
  return Render(equal, spec, true, items, draw, plot_area_px);
}

MosaicOptions::MosaicOptions() { Table().FillDefaults(this); }

const OptionTable<MosaicOptions>& MosaicOptions::Table() {
  using O = MosaicOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("scale", &O::scale, 2, "", R::Closed(1, 16), "upscaling factor per tile (nearest neighbour)")
          .Add("gap_px", &O::gap_px, 4, "px", R::Closed(0, 100), "white gap between tiles and between rows")
          .Add("font_scale", &O::font_scale, 0.5, "", R::Closed(0.3, 2), "caption size (OpenCV Hershey scale)");
  return table;
}

std::string MosaicOptions::Check() const { return Table().FirstProblem(*this); }

cv::Mat MatchMosaic(const std::vector<std::vector<MatchTile>>& rows, const MosaicOptions& options) {
  HOILCD_CHECK_MSG(options.Check().empty(), options.Check());
  std::vector<std::vector<cv::Mat>> rendered(rows.size());
  int width = 0;
  int height = 0;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    cv::Size largest(0, 0);
    for (const MatchTile& tile : rows[r]) {
      largest.width = std::max(largest.width, tile.image.cols * options.scale);
      largest.height = std::max(largest.height, tile.image.rows * options.scale);
    }
    if (largest.area() == 0) largest = cv::Size(64, 48) * options.scale;
    int row_width = 0;
    int row_height = 0;
    for (const MatchTile& tile : rows[r]) {
      rendered[r].push_back(RenderTile(tile, largest, options));
      row_width += rendered[r].back().cols + (row_width > 0 ? options.gap_px : 0);
      row_height = std::max(row_height, rendered[r].back().rows);
    }
    width = std::max(width, row_width);
    height += row_height + (r > 0 ? options.gap_px : 0);
  }
  cv::Mat mosaic(std::max(1, height), std::max(1, width), CV_8UC3, White());
  int top = 0;
  for (const std::vector<cv::Mat>& row : rendered) {
    int left = 0;
    int row_height = 0;
    for (const cv::Mat& tile : row) {
      tile.copyTo(mosaic(cv::Rect(left, top, tile.cols, tile.rows)));
      left += tile.cols + options.gap_px;
      row_height = std::max(row_height, tile.rows);
    }
    top += row_height + options.gap_px;
  }
  return mosaic;
}

}  // namespace hoilcd
