// Reflections in glossy surfaces, from the EXR ground truth: a whiteboard or a window that mirrors
// a warm body shows a spread of true temperature across its own pixels that a plain one does not.
#include <algorithm>
#include <array>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "hoilcd/bench/report/inspect.h"
#include "hoilcd/core/dataset/exr_io.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/core/util/stats.h"

namespace hoilcd {

namespace {

// p98 − p2 of the true temperature over one class's interior pixels (one pixel in from any other
// class, so edges and their supersampling do not count), or −1 when fewer than kMinPixels show it.
constexpr int kMinPixels = 100;
double InteriorSpreadK(const cv::Mat& t, const cv::Mat& cls, int id) {
  if (id < 0) return -1;
  cv::Mat mask = cls == static_cast<float>(id);
  cv::erode(mask, mask, cv::Mat::ones(3, 3, CV_8U));
  std::vector<double> values;
  for (int y = 0; y < t.rows; ++y) {
    for (int x = 0; x < t.cols; ++x)
      if (mask.at<uint8_t>(y, x)) values.push_back(t.at<float>(y, x));
  }
  if (static_cast<int>(values.size()) < kMinPixels) return -1;
  return Quantile(values, 0.98) - Quantile(values, 0.02);
}

}  // namespace

std::vector<InspectFigure> ReflectionFigures(const Dataset& dataset, const std::vector<int>& frames, int threads) {
  const DatasetManifest& manifest = dataset.manifest();
  const char* kinds[] = {"whiteboard", "window"};
  std::vector<std::array<double, 2>> spread(frames.size());
  ParallelFor(static_cast<int64_t>(frames.size()), threads, [&](int64_t i) {
    const int frame = frames[static_cast<size_t>(i)];
    const ExrChannels channels = ReadDatasetExr(dataset, frame);
    const std::string path = DatasetExrPath(dataset, frame);
    const cv::Mat& t = ExrChannel(channels, "T_true", path);
    const cv::Mat& cls = ExrChannel(channels, "class", path);
    for (int k = 0; k < 2; ++k) {
      const auto it = manifest.classes.find(kinds[k]);
      spread[static_cast<size_t>(i)][k] = InteriorSpreadK(t, cls, it == manifest.classes.end() ? -1 : it->second);
    }
  });
  std::vector<InspectFigure> figures;
  for (int k = 0; k < 2; ++k) {
    std::vector<double> seen;
    for (const auto& s : spread)
      if (s[k] >= 0) seen.push_back(s[k]);
    const std::string kind = kinds[k];
    figures.push_back(NumberFigure(kind + "_views",
                                   kind + " views (at least " + std::to_string(kMinPixels) + " interior pixels)",
                                   static_cast<double>(seen.size()), ""));
    if (seen.empty()) continue;
    figures.push_back(NumberFigure(kind + "_spread_median_k", kind + " true temperature spread (p98 - p2), median",
                                   Median(seen), "K"));
    figures.push_back(NumberFigure(kind + "_spread_max_k",
                                   kind + " true temperature spread (p98 - p2), max: its strongest reflection",
                                   *std::max_element(seen.begin(), seen.end()), "K"));
  }
  return figures;
}

}  // namespace hoilcd
