#include "hoilcd/core/util/stats.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "hoilcd/core/util/error.h"

namespace hoilcd {

double Mean(const std::vector<double>& values) {
  if (values.empty()) return NAN;
  return std::accumulate(values.begin(), values.end(), 0.0) / values.size();
}

double StdDev(const std::vector<double>& values) {
  if (values.empty()) return NAN;
  if (values.size() == 1) return 0.0;
  const double mean = Mean(values);
  double squares = 0;
  for (double v : values) squares += (v - mean) * (v - mean);
  return std::sqrt(squares / (values.size() - 1));
}

double Quantile(std::vector<double> values, double q) {
  HOILCD_CHECK_MSG(q >= 0.0 && q <= 1.0, "quantile " << q << " outside [0, 1]");
  if (values.empty()) return NAN;
  std::sort(values.begin(), values.end());
  const double at = q * (values.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(at));
  const size_t hi = std::min(lo + 1, values.size() - 1);
  return values[lo] + (at - lo) * (values[hi] - values[lo]);
}

double Median(std::vector<double> values) {
  if (values.empty()) return NAN;
  const size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + mid, values.end());
  if (values.size() % 2 == 1) return values[mid];
  return 0.5 * (values[mid] + *std::max_element(values.begin(), values.begin() + mid));
}

}  // namespace hoilcd
