#include "hoilcd/bench/report/inspect_walls.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "hoilcd/core/dataset/exr_io.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/core/util/stats.h"

namespace hoilcd {
namespace {

struct SurfaceSpread {
  double wall_k = NAN;       // p95 − p5 over wall pixels; NaN when too few
  double structure_k = NAN;  // the same over wall, ceiling and floor pixels
};

double Spread(std::vector<double> values) {
  if (values.size() < static_cast<size_t>(kMinSurfacePixels)) return NAN;
  return Quantile(values, 0.95) - Quantile(std::move(values), 0.05);
}

SurfaceSpread SpreadOf(const Dataset& dataset, int frame) {
  const ExrChannels channels = ReadDatasetExr(dataset, frame);
  const std::string path = DatasetExrPath(dataset, frame);
  const cv::Mat& t = ExrChannel(channels, "T_true", path);
  const cv::Mat& cls = ExrChannel(channels, "class", path);
  const DatasetManifest& manifest = dataset.manifest();
  const int wall = manifest.ClassId("wall");
  const std::set<int> structure = {wall, manifest.ClassId("floor"), manifest.ClassId("ceiling")};
  std::vector<double> walls, all;
  for (int y = 0; y < t.rows; ++y) {
    for (int x = 0; x < t.cols; ++x) {
      const int k = static_cast<int>(cls.at<float>(y, x));
      if (!structure.count(k)) continue;
      all.push_back(t.at<float>(y, x));
      if (k == wall) walls.push_back(t.at<float>(y, x));
    }
  }
  return {Spread(std::move(walls)), Spread(std::move(all))};
}

double MedianOfKnown(const std::vector<double>& values, int* count) {
  std::vector<double> known;
  for (double v : values)
    if (!std::isnan(v)) known.push_back(v);
  *count = static_cast<int>(known.size());
  return known.empty() ? NAN : Median(known);
}

}  // namespace

InspectSection WallSection(const Dataset& dataset, int threads) {
  InspectSection s{"walls", "Room surfaces (true temperature, EXR)", {}};
  const std::vector<int> sampled = SampledViewFrames(dataset);
  std::vector<SurfaceSpread> spreads(sampled.size());
  ParallelFor(static_cast<int64_t>(sampled.size()), threads,
              [&](int64_t i) { spreads[static_cast<size_t>(i)] = SpreadOf(dataset, sampled[static_cast<size_t>(i)]); });
  std::vector<double> wall, structure;
  for (const SurfaceSpread& v : spreads) {
    wall.push_back(v.wall_k);
    structure.push_back(v.structure_k);
  }
  int wall_views = 0, structure_views = 0;
  const double wall_median = MedianOfKnown(wall, &wall_views);
  const double structure_median = MedianOfKnown(structure, &structure_views);
  const std::string enough = " (views with at least " + std::to_string(kMinSurfacePixels) + " px)";
  s.figures = {
      NumberFigure("wall_views", "views showing wall" + enough, wall_views, ""),
      NumberFigure("wall_spread_median_k", "wall true temperature spread (p95 - p5), median", wall_median, "K"),
      NumberFigure("structure_spread_median_k", "wall, ceiling and floor spread (p95 - p5), median", structure_median,
                   "K"),
  };
  return s;
}

}  // namespace hoilcd
