#include "hoilcd/bench/report/realism_report.h"

#include <algorithm>
#include <cmath>

#include "hoilcd/bench/report/chart.h"
#include "hoilcd/bench/report/output_folder.h"
#include "hoilcd/core/util/file_io.h"

namespace hoilcd {
namespace {

constexpr int kBins = 30;

OutputMarker RealismMarker() {
  return {"realism.json", {"hoilcd_version", "statistics", "real", "synthetic"}, "realism output"};
}

// A histogram as a step line of densities (each side sums to 1 over the bins).
Series StepSeries(const std::string& label, const std::vector<double>& values, double lo, double width, size_t colour) {
  Series s;
  s.label = label + " (n " + std::to_string(values.size()) + ")";
  s.colour = PaletteColour(colour);
  if (values.empty()) return s;
  std::vector<double> counts(kBins, 0.0);
  for (double v : values) {
    const int bin = std::clamp(static_cast<int>(std::floor((v - lo) / width)), 0, kBins - 1);
    counts[static_cast<size_t>(bin)] += 1;
  }
  for (int b = 0; b < kBins; ++b) {
    const double share = counts[static_cast<size_t>(b)] / static_cast<double>(values.size());
    s.x.push_back(lo + b * width);
    s.y.push_back(share);
    s.x.push_back(lo + (b + 1) * width);
    s.y.push_back(share);
  }
  return s;
}

cv::Mat Panel(const StatisticRow& row, const std::vector<double>& synthetic, const std::vector<double>& real,
              const std::string& title) {
  double lo = INFINITY, hi = -INFINITY;
  for (const auto* side : {&synthetic, &real}) {
    for (double v : *side) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  if (!(lo <= hi)) {  // neither side has a value
    lo = 0;
    hi = 1;
  }
  if (hi - lo < 1e-9) {  // one value: a bin around it
    lo -= 0.5;
    hi += 0.5;
  }
  const double width = (hi - lo) / kBins;
  PlotOptions o;
  o.title = title;
  o.x_label = row.label + (row.unit.empty() ? "" : ", " + row.unit);
  o.y_label = "share of frames";
  o.width_px = 640;
  o.height_px = 420;
  return LinePlot({StepSeries("real", real, lo, width, 1), StepSeries("synthetic", synthetic, lo, width, 0)}, o);
}

}  // namespace

void CheckRealismFolder(const std::string& dir) { CheckOutputFolder(dir, RealismMarker()); }

cv::Mat RealismHistogram(const StatisticRow& row) {
  cv::Mat out;
  cv::hconcat(Panel(row, row.synthetic, row.real, "every view"),
              Panel(row, row.synthetic_not_blank, row.real_not_blank, "views that are not blank"), out);
  return out;
}

void WriteRealismFolder(const RealismComparison& comparison, const std::string& dir) {
  CheckRealismFolder(dir);
  CreateOutputFolder(dir);
  CreateOutputFolder(dir + "/histograms");
  for (const StatisticRow& row : comparison.rows)
    WritePng(dir + "/histograms/" + row.key + ".png", RealismHistogram(row));
  WriteFileAtomic(dir + "/realism.md", comparison.ToMarkdown());
  // The marker last: a folder holding it holds a whole earlier output.
  WriteFileAtomic(dir + "/realism.json", comparison.ToJson().dump(2) + "\n");
}

InspectSection FrameStatisticsSection(const Dataset& dataset, int threads) {
  InspectSection s{
      "frame_statistics", "Frame statistics (as hoilcd realism measures them; compare with real frames)", {}};
  const FrameSet frames = MeasureDatasetFrames(dataset, SampledViewFrames(dataset), threads);
  const RealismComparison c = CompareFrameSets(frames, {});
  s.figures.push_back(NumberFigure("frames", "frames measured", static_cast<double>(frames.frames.size()), ""));
  const int radiometric = frames.Radiometric();
  s.figures.push_back(NumberFigure("blank_views_pct", "blank views (radiometric p95 - p5 < 2 K), %",
                                   radiometric > 0 ? 100.0 * frames.Blank() / radiometric : NAN, "%"));
  for (const StatisticRow& row : c.rows) {
    const bool noise = row.key == "temporal_noise_k";
    const std::string unit = row.unit == "°C" ? "C" : row.unit;
    s.figures.push_back(NumberFigure(row.key + "_median", row.label + ", median" + (noise ? " over static pairs" : ""),
                                     row.all.synthetic.median, unit));
    if (!noise) {
      s.figures.push_back(NumberFigure(row.key + "_median_not_blank", row.label + ", median over views not blank",
                                       row.not_blank.synthetic.median, unit));
    }
  }
  s.figures.push_back(NumberFigure("static_pairs", "static pairs (camera moved < 2 mm and 0.02 deg)",
                                   static_cast<double>(frames.temporal_noise_k.size()), ""));
  return s;
}

}  // namespace hoilcd
