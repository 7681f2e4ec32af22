// The inspect section on clothing: how much a person's clothing varies within itself, from the
// EXR ground truth alone (T_true, id, class). Clothing is told from skin by temperature (see
// ClothingSection in inspect.h for the rule and its limits).
#include <algorithm>
#include <map>

#include "hoilcd/bench/report/inspect.h"
#include "hoilcd/core/dataset/exr_io.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/core/util/stats.h"

namespace hoilcd {
namespace {

struct FrameClothing {
  int64_t pairs = 0, equal_pairs = 0;
  std::vector<double> spreads_k;  // p95 - p5 of each person's clothing pixels (enough of them)
};

FrameClothing MeasureFrame(const Dataset& dataset, int frame) {
  const ExrChannels channels = ReadDatasetExr(dataset, frame);
  const std::string path = DatasetExrPath(dataset, frame);
  const cv::Mat& t = ExrChannel(channels, "T_true", path);
  const cv::Mat& id = ExrChannel(channels, "id", path);
  const cv::Mat& cls = ExrChannel(channels, "class", path);
  const int person = dataset.manifest().ClassId("person");
  // Clothing: an interior person pixel (its four neighbours show the same person) in the band.
  cv::Mat who(t.size(), CV_32S, cv::Scalar(-1));
  for (int y = 1; y + 1 < t.rows; ++y) {
    for (int x = 1; x + 1 < t.cols; ++x) {
      if (static_cast<int>(cls.at<float>(y, x)) != person) continue;
      const float v = t.at<float>(y, x), label = id.at<float>(y, x);
      if (v < kClothingMinC || v >= kClothingMaxC) continue;
      if (id.at<float>(y - 1, x) != label || id.at<float>(y + 1, x) != label || id.at<float>(y, x - 1) != label ||
          id.at<float>(y, x + 1) != label)
        continue;
      who.at<int>(y, x) = static_cast<int>(label);
    }
  }
  FrameClothing out;
  std::map<int, std::vector<double>> by_person;
  for (int y = 0; y < t.rows; ++y) {
    for (int x = 0; x < t.cols; ++x) {
      const int w = who.at<int>(y, x);
      if (w < 0) continue;
      by_person[w].push_back(t.at<float>(y, x));
      for (const auto& [nx, ny] : {std::pair<int, int>{x + 1, y}, std::pair<int, int>{x, y + 1}}) {
        if (nx >= t.cols || ny >= t.rows || who.at<int>(ny, nx) != w) continue;
        ++out.pairs;
        out.equal_pairs += std::abs(t.at<float>(ny, nx) - t.at<float>(y, x)) <= kEqualClothingK;
      }
    }
  }
  for (const auto& [w, values] : by_person) {
    if (values.size() >= kClothingMinPixels) out.spreads_k.push_back(Quantile(values, 0.95) - Quantile(values, 0.05));
  }
  return out;
}

}  // namespace

InspectSection ClothingSection(const Dataset& dataset, int threads) {
  InspectSection s{"clothing", "Clothing within a person (true temperature, EXR)", {}};
  const std::vector<int> sampled = SampledViewFrames(dataset);
  std::vector<FrameClothing> measured(sampled.size());
  ParallelFor(static_cast<int64_t>(sampled.size()), threads, [&](int64_t i) {
    measured[static_cast<size_t>(i)] = MeasureFrame(dataset, sampled[static_cast<size_t>(i)]);
  });
  int64_t pairs = 0, equal = 0;
  std::vector<double> spreads;
  for (const FrameClothing& f : measured) {
    pairs += f.pairs;
    equal += f.equal_pairs;
    spreads.insert(spreads.end(), f.spreads_k.begin(), f.spreads_k.end());
  }
  s.figures = {
      NumberFigure("neighbour_pairs", "neighbouring clothing pixel pairs of one person", static_cast<double>(pairs),
                   ""),
      NumberFigure("equal_neighbours_percent", "of them within 0.02 K of each other",
                   pairs ? 100.0 * static_cast<double>(equal) / static_cast<double>(pairs) : 0, "%"),
      NumberFigure("spread_median_k", "p95 - p5 within a person's clothing in a frame, median", Median(spreads), "K"),
  };
  return s;
}

}  // namespace hoilcd
