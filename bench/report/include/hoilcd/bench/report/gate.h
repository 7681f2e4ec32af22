// The CI gate: a run's report.json against a baseline report.json. Every method present in both
// is compared on the headline metrics (MRR, R@1); a drop larger than the allowed one is a
// regression. Also JUnit XML of a report, one test case per method, for CI dashboards.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hoilcd/bench/evaluation/report_json.h"  // ReadReportJson, kHeadlineMetrics

namespace hoilcd {

struct Regression {
  std::string method;
  std::string metric;  // "mrr" or "recall_at_1"
  double old_value = 0;
  double new_value = 0;  // NaN when the new run has no value (no query scored)
  std::string ToString(double max_drop) const;  // one line: method, metric, old, new
};

// The regressions of `current` against `baseline` (both report.json documents), in baseline
// method order then metric order. A metric the baseline lacks (null) is not compared.
std::vector<Regression> CompareToBaseline(const nlohmann::json& baseline, const nlohmann::json& current,
                                          double max_drop);

// Methods of the baseline missing from `current` (not compared; the CLI names them).
std::vector<std::string> MethodsOnlyInBaseline(const nlohmann::json& baseline, const nlohmann::json& current);

// JUnit XML: a test suite "hoilcd" with one test case per method of `report`, failing with one
// <failure> per regression of that method.
std::string JUnitXml(const nlohmann::json& report, const std::vector<Regression>& regressions, double max_drop);

}  // namespace hoilcd
