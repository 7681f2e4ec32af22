// Uncertainty of the headline metrics: a circular block bootstrap over the queries in time order
// (Politis & Romano 1992). Neighbouring queries see nearly the same view and score alike, so
// queries are resampled in blocks as long as their reciprocal ranks stay correlated, chosen from
// the data (Politis & White 2004, corrected by Patton, Politis & White 2009). Every metric of a
// resample is recomputed from its per-query records (metrics.h SummariseQueries), so an interval
// covers exactly what the headline reports. Paired comparisons resample the same blocks for both
// methods. Resamples are keyed by (seed, index): the same records give the same intervals at any
// thread count.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hoilcd/bench/evaluation/metrics.h"
#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

struct BootstrapOptions {
  int resamples;      // bootstrap resamples
  double confidence;  // of the two-sided percentile interval
  uint64_t seed;      // of the block draws

  BootstrapOptions();  // the registered defaults
  static const OptionTable<BootstrapOptions>& Table();
  std::string Check() const;
};

struct Interval {
  double low = NAN;
  double high = NAN;
  bool Contains(double value) const { return value >= low && value <= high; }
  nlohmann::json ToJson() const;  // [low, high]; null ends when not computed
};

// The interval of every headline metric of one method.
struct HeadlineIntervals {
  Interval mrr, recall_at_1, recall_at_5, recall_at_10, pr_auc, recall_at_100p;
  nlohmann::json ToJson() const;  // {"mrr": [low, high], ...}; null ends when not computed
};

// How the queries were resampled, for the report.
struct BootstrapPlan {
  int block_queries = 1;  // queries per block
  double block_s = 0;     // the time a block spans, s
  int resamples = 0;
  double confidence = 0;
  nlohmann::json ToJson() const;
};

// The circular block bootstrap's block length for one series (Politis & White 2004 with the 2009
// correction): from the lag where its autocorrelation stops being significant and a flat-top
// lag-window estimate of its spectrum; 1 for an uncorrelated or constant series, at most
// min(3 sqrt(n), n / 3).
double OptimalBlockLength(const std::vector<double>& series);

// The plan for methods scored on the same queries (each a MethodMetrics::queries, in query order):
// blocks of the longest OptimalBlockLength of their per-query reciprocal ranks (rounded up), so
// one plan serves every interval and paired comparison. `frame_rate_hz` turns it into seconds.
BootstrapPlan PlanBootstrap(const std::vector<const std::vector<QueryRecord>*>& methods, double frame_rate_hz,
                            const BootstrapOptions& options);

// The percentile intervals of a method's headline metrics (records: its MethodMetrics::queries).
// Resamples without a scored query are left out of the interval. `threads`: 0 = every CPU.
HeadlineIntervals BootstrapHeadline(const std::vector<QueryRecord>& records, const BootstrapPlan& plan, uint64_t seed,
                                    int threads = 0);

// A paired comparison on MRR: the mean difference of per-query reciprocal ranks over the queries
// both methods scored, and its interval from the same resampled blocks for both.
struct PairedComparison {
  std::string a, b;    // written as "a > b" when delta >= 0 (a the better)
  double delta = NAN;  // MRR(a) - MRR(b)
  Interval interval;   // of delta
  int queries = 0;     // scored by both
  bool Separated() const { return interval.low > 0 || interval.high < 0; }  // the interval excludes 0
  std::string ToString() const;                                             // "slcd > dlcd: Δ 0.081 [0.050, 0.110]"
  nlohmann::json ToJson() const;
};

PairedComparison PairedBootstrap(const std::string& name_a, const std::vector<QueryRecord>& a,
                                 const std::string& name_b, const std::vector<QueryRecord>& b,
                                 const BootstrapPlan& plan, uint64_t seed, int threads = 0);

}  // namespace hoilcd
