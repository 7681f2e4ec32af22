// The CI gate: a run's report.json against a baseline report.json. Every method present in both
// is compared on the headline metrics (MRR, R@1); a drop larger than the allowed one (a fixed
// amount, or what the run's own 95 % interval leaves to chance) is a regression. Also JUnit XML of a report, one test
// case per method, for CI dashboards.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hoilcd/bench/evaluation/report_json.h"  // ReadReportJson, kHeadlineMetrics

namespace hoilcd {

// How far a headline metric may drop (--max-drop X|ci).
struct DropAllowance {
  DropAllowance(double max_drop = 0) : max_drop(max_drop) {}  // NOLINT: a number is an allowance
  // "ci": a drop is a regression only when the baseline's value lies above the upper end of the
  // current run's 95 % interval of that metric (methods.<name>.intervals; a metric without one
  // counts as an interval of zero width), so a change the query sample explains passes.
  bool interval = false;
  double max_drop = 0;  // the fixed allowance when !interval
  // "0.01" or "ci"; InputError at `where` otherwise ("expected a number in [0, 1] or 'ci'").
  static DropAllowance Parse(const std::string& text, const std::string& where);
  std::string ToString() const;  // "by more than 0.0100" / "beyond the run's 95 % interval"
};

struct Regression {
  std::string method;
  std::string metric;  // "mrr" or "recall_at_1"
  double old_value = 0;
  double new_value = 0;                                      // NaN when the new run has no value (no query scored)
  double new_low = NAN, new_high = NAN;                      // the new run's interval (DropAllowance::interval)
  std::string ToString(const DropAllowance& allowed) const;  // one line: method, metric, old, new
};

// The regressions of `current` against `baseline` (both report.json documents), in baseline
// method order then metric order. A metric the baseline lacks (null) is not compared.
std::vector<Regression> CompareToBaseline(const nlohmann::json& baseline, const nlohmann::json& current,
                                          const DropAllowance& allowed);

// Methods of the baseline missing from `current` (not compared; the CLI names them).
std::vector<std::string> MethodsOnlyInBaseline(const nlohmann::json& baseline, const nlohmann::json& current);

// JUnit XML: a test suite "hoilcd" with one test case per method of `report`, failing with one
// <failure> per regression of that method.
std::string JUnitXml(const nlohmann::json& report, const std::vector<Regression>& regressions,
                     const DropAllowance& allowed);

}  // namespace hoilcd
