#include "hoilcd/bench/evaluation/bootstrap.h"

#include <algorithm>
#include <cstdio>

#include "hoilcd/bench/evaluation/json_number.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/core/util/random.h"
#include "hoilcd/core/util/stats.h"

namespace hoilcd {
namespace {

// The query indices of resample `index`: ceil(n / L) blocks of L consecutive queries, each
// starting anywhere and wrapping past the end (circular), cut to n.
std::vector<int> ResampleIndices(int n, int block, uint64_t seed, int64_t index) {
  Rng rng = KeyedRng(seed, "bootstrap.blocks", index);
  std::vector<int> out;
  out.reserve(n);
  while (static_cast<int>(out.size()) < n) {
    const int start = static_cast<int>(rng.UniformInt(static_cast<uint32_t>(n)));
    for (int k = 0; k < block && static_cast<int>(out.size()) < n; ++k) out.push_back((start + k) % n);
  }
  return out;
}

Interval PercentileInterval(const std::vector<double>& values, double confidence) {
  std::vector<double> finite;
  for (double v : values)
    if (std::isfinite(v)) finite.push_back(v);
  const double tail = (1 - confidence) / 2;
  return {Quantile(finite, tail), Quantile(std::move(finite), 1 - tail)};
}

}  // namespace

nlohmann::json Interval::ToJson() const { return nlohmann::json::array({JsonNumber(low), JsonNumber(high)}); }

BootstrapOptions::BootstrapOptions() { Table().FillDefaults(this); }

const OptionTable<BootstrapOptions>& BootstrapOptions::Table() {
  using O = BootstrapOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("resamples", &O::resamples, 1000, "", R::Closed(10, 100000),
               "bootstrap resamples of the queries (each recomputes every metric)")
          .Add("confidence", &O::confidence, 0.95, "", R::Any().Above(0).Below(1),
               "coverage of the two-sided percentile interval")
          .Add("seed", &O::seed, uint64_t{0}, "", R::Any().AtLeast(0), "seed of the block draws");
  return table;
}

std::string BootstrapOptions::Check() const { return Table().FirstProblem(*this); }

nlohmann::json HeadlineIntervals::ToJson() const {
  return {{"mrr", mrr.ToJson()},
          {"recall_at_1", recall_at_1.ToJson()},
          {"recall_at_5", recall_at_5.ToJson()},
          {"recall_at_10", recall_at_10.ToJson()},
          {"pr_auc", pr_auc.ToJson()},
          {"recall_at_100p", recall_at_100p.ToJson()}};
}

nlohmann::json BootstrapPlan::ToJson() const {
  return {{"method", "circular block bootstrap over the queries in time order"},
          {"block_queries", block_queries},
          {"block_s", block_s},
          {"block_length",
           "Politis & White (2004, corrected 2009): the longest over the methods of the optimal "
           "circular-block length of their per-query reciprocal ranks"},
          {"resamples", resamples},
          {"confidence", confidence},
          {"interval", "percentile"}};
}

// Written out here: no Debian C++ library selects bootstrap block lengths (R's np and Python's
// arch do). Follows the paper's recipe with its published constants.
double OptimalBlockLength(const std::vector<double>& series) {
  const int n = static_cast<int>(series.size());
  if (n < 4) return 1;
  double mean = 0;
  for (double v : series) mean += v;
  mean /= n;
  const int kn = std::max(5, static_cast<int>(std::ceil(std::sqrt(std::log10(n)))));
  const int max_lag = std::min(n - 1, static_cast<int>(std::ceil(std::sqrt(n))) + kn);
  std::vector<double> cov(max_lag + 1, 0.0);  // R(k), biased (1/n)
  for (int k = 0; k <= max_lag; ++k) {
    for (int i = 0; i + k < n; ++i) cov[k] += (series[i] - mean) * (series[i + k] - mean);
    cov[k] /= n;
  }
  if (cov[0] <= 0) return 1;  // constant
  // m: the smallest lag after which kn autocorrelations in a row are insignificant.
  const double bound = 2 * std::sqrt(std::log10(n) / n);
  int m = -1;
  for (int start = 0; start + kn <= max_lag && m < 0; ++start) {
    bool quiet = true;
    for (int j = 1; j <= kn && quiet; ++j) quiet = std::abs(cov[start + j] / cov[0]) < bound;
    if (quiet) m = start;
  }
  if (m < 0) m = max_lag;  // correlated at every lag looked at
  const int big_m = std::min(2 * m, max_lag);
  // Flat-top lag window: 1 up to M/2, falling linearly to 0 at M.
  const auto window = [&](int k) {
    const double t = big_m == 0 ? 0 : std::abs(static_cast<double>(k)) / big_m;
    return t <= 0.5 ? 1.0 : t <= 1 ? 2 * (1 - t) : 0.0;
  };
  double g = 0, spectrum = cov[0];
  for (int k = 1; k <= big_m; ++k) {
    g += 2 * window(k) * k * cov[k];
    spectrum += 2 * window(k) * cov[k];
  }
  const double d_cb = 4.0 / 3.0 * spectrum * spectrum;
  const double b_max = std::ceil(std::min(3 * std::sqrt(n), n / 3.0));
  if (d_cb <= 0) return 1;
  return std::clamp(std::cbrt(2 * g * g / d_cb) * std::cbrt(n), 1.0, b_max);
}

BootstrapPlan PlanBootstrap(const std::vector<const std::vector<QueryRecord>*>& methods, double frame_rate_hz,
                            const BootstrapOptions& options) {
  HOILCD_CHECK_MSG(options.Check().empty(), options.Check());
  HOILCD_CHECK(frame_rate_hz > 0);
  BootstrapPlan plan;
  plan.resamples = options.resamples;
  plan.confidence = options.confidence;
  double longest = 1;
  size_t queries = 0;
  int first = 0, last = 0;
  for (const std::vector<QueryRecord>* records : methods) {
    std::vector<double> reciprocal_ranks;
    for (const QueryRecord& r : *records)
      if (r.scored) reciprocal_ranks.push_back(r.reciprocal_rank);
    longest = std::max(longest, OptimalBlockLength(reciprocal_ranks));
    queries = records->size();
    if (!records->empty()) first = records->front().frame, last = records->back().frame;
  }
  plan.block_queries = static_cast<int>(std::ceil(longest));
  // The time a block spans: its queries at the rate queries come in.
  if (queries > 1) plan.block_s = plan.block_queries * (last - first + 1) / frame_rate_hz / queries;
  return plan;
}

HeadlineIntervals BootstrapHeadline(const std::vector<QueryRecord>& records, const BootstrapPlan& plan, uint64_t seed,
                                    int threads) {
  HeadlineIntervals out;
  const int n = static_cast<int>(records.size());
  if (n == 0 || plan.resamples <= 0) return out;
  enum { kMrr, kR1, kR5, kR10, kPrAuc, kR100p, kMetrics };
  std::vector<std::vector<double>> values(kMetrics, std::vector<double>(plan.resamples, NAN));
  ParallelFor(plan.resamples, threads, [&](int64_t b) {
    std::vector<QueryRecord> resample;
    resample.reserve(n);
    for (int i : ResampleIndices(n, plan.block_queries, seed, b)) resample.push_back(records[i]);
    const MethodMetrics m = SummariseQueries(std::move(resample));
    const double figures[kMetrics] = {m.mrr, m.recall_at_1, m.recall_at_5, m.recall_at_10, m.pr_auc, m.recall_at_100p};
    for (int k = 0; k < kMetrics; ++k) values[k][b] = figures[k];
  });
  out.mrr = PercentileInterval(values[kMrr], plan.confidence);
  out.recall_at_1 = PercentileInterval(values[kR1], plan.confidence);
  out.recall_at_5 = PercentileInterval(values[kR5], plan.confidence);
  out.recall_at_10 = PercentileInterval(values[kR10], plan.confidence);
  out.pr_auc = PercentileInterval(values[kPrAuc], plan.confidence);
  out.recall_at_100p = PercentileInterval(values[kR100p], plan.confidence);
  return out;
}

PairedComparison PairedBootstrap(const std::string& name_a, const std::vector<QueryRecord>& a,
                                 const std::string& name_b, const std::vector<QueryRecord>& b,
                                 const BootstrapPlan& plan, uint64_t seed, int threads) {
  HOILCD_CHECK_MSG(a.size() == b.size(),
                   "a paired comparison needs the same queries (" << a.size() << " vs " << b.size() << ")");
  const int n = static_cast<int>(a.size());
  // Per query: RR(a) - RR(b) where both scored it, else not counted.
  std::vector<double> difference(n, NAN);
  double sum = 0;
  PairedComparison out;
  for (int i = 0; i < n; ++i) {
    HOILCD_CHECK_MSG(a[i].frame == b[i].frame, "a paired comparison needs the same queries in the same order");
    if (!a[i].scored || !b[i].scored) continue;
    difference[i] = a[i].reciprocal_rank - b[i].reciprocal_rank;
    sum += difference[i];
    ++out.queries;
  }
  if (out.queries == 0) return out;
  std::vector<double> deltas(plan.resamples, NAN);
  ParallelFor(plan.resamples, threads, [&](int64_t r) {
    double total = 0;
    int count = 0;
    for (int i : ResampleIndices(n, plan.block_queries, seed, r)) {
      if (std::isnan(difference[i])) continue;
      total += difference[i];
      ++count;
    }
    if (count > 0) deltas[r] = total / count;
  });
  const double delta = sum / out.queries;
  const Interval interval = PercentileInterval(deltas, plan.confidence);
  const bool a_better = delta >= 0;
  out.a = a_better ? name_a : name_b;
  out.b = a_better ? name_b : name_a;
  out.delta = a_better ? delta : -delta;
  out.interval = a_better ? interval : Interval{-interval.high, -interval.low};
  return out;
}

std::string PairedComparison::ToString() const {
  char text[200];
  std::snprintf(text, sizeof(text), "%s > %s: \xce\x94 %.3f [%.3f, %.3f]", a.c_str(), b.c_str(), delta, interval.low,
                interval.high);
  return text;
}

nlohmann::json PairedComparison::ToJson() const {
  return {{"better", a},
          {"worse", b},
          {"delta_mrr", JsonNumber(delta)},
          {"interval", interval.ToJson()},
          {"queries", queries},
          {"separated", Separated()}};
}

}  // namespace hoilcd
