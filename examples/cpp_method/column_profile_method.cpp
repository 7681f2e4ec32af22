#include "column_profile_method.h"

#include <chrono>
#include <cmath>

#include <opencv2/core.hpp>

#include "hoilcd/bench/runner/runner.h"

namespace {

using Clock = std::chrono::steady_clock;

double MsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

class ColumnProfile : public hoilcd::LoopClosureMethod {
 public:
  std::string Name() const override { return "column-profile"; }
  std::string Description() const override {
    return "example (examples/cpp_method): negative L1 distance of per-column mean intensity";
  }
  hoilcd::MethodScores Score(const hoilcd::MethodContext& c) const override {
    const int frames = c.dataset.num_frames();
    std::vector<cv::Mat> profiles(frames);  // 1 x W, CV_64F
    std::vector<double> extract_ms(frames);
    for (int f = 0; f < frames; ++f) {
      const Clock::time_point start = Clock::now();
      cv::reduce(c.dataset.Thermal(f), profiles[f], 0, cv::REDUCE_AVG, CV_64F);
      extract_ms[f] = MsSince(start);
    }
    hoilcd::MethodScores out;
    for (const hoilcd::Query& q : c.queries()) {
      const Clock::time_point start = Clock::now();
      std::vector<double> scores;
      for (int r : q.database) scores.push_back(-cv::norm(profiles[q.frame], profiles[r], cv::NORM_L1));
      out.scores.push_back(std::move(scores));
      out.match_ms.push_back(MsSince(start));
    }
    out.extract_ms = c.PerQuery(extract_ms);
    return out;
  }
};

}  // namespace

std::unique_ptr<hoilcd::LoopClosureMethod> MakeColumnProfileMethod() { return std::make_unique<ColumnProfile>(); }
