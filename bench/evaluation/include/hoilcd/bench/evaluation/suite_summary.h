// The summary of a benchmark suite (`hoilcd suite`): per method, each run's MRR and R@1, their
// mean over runs with a percentile bootstrap interval, each method's rank per run and mean rank,
// and paired wins for every pair of methods. Built from numbers alone, so it is tested on
// constructed values; the pipeline (suite.h) fills it from the runs' report.json files.
#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "hoilcd/bench/evaluation/bootstrap.h"

namespace hoilcd {

// One (sequence, seed) of a suite: its metrics per method, or the error that stopped it.
struct SuiteRunResult {
  std::string name;                          // "<sequence>-seed<S>": the run's identity
  std::string error;                         // empty when the run finished
  std::map<std::string, double> mrr;         // method -> MRR (NaN: no scored query)
  std::map<std::string, double> recall_at_1; // method -> R@1
  bool ok() const { return error.empty(); }
};

// The interval over runs: runs are resampled i.i.d. (the sequences are independent renders, so
// unlike the queries of one sequence they carry no serial correlation), keyed by (seed, resample).
struct SuiteBootstrapOptions {
  int resamples = 2000;     // bootstrap resamples
  double confidence = 0.95; // of the two-sided percentile interval
  uint64_t seed = 1;        // of the resampling: fixed, so a report is byte-reproducible
};

// One method over the finished runs.
struct SuiteMethodSummary {
  std::string method;
  std::vector<double> mrr, recall_at_1;  // per finished run, in run order
  std::vector<double> rank;              // per finished run: 1 = best MRR, ties share the mean rank
  double mean_mrr = NAN, mean_recall_at_1 = NAN, mean_rank = NAN;
  Interval mrr_interval, recall_at_1_interval;  // of the means
};

// How often `a` beat `b` on MRR over the finished runs.
struct SuiteWins {
  std::string a, b;
  int a_wins = 0, b_wins = 0, ties = 0;
  std::string ToString() const;  // "slcd beats dlcd on 9 of 12 (2 ties)"
};

struct SuiteSummary {
  std::string name, description;
  nlohmann::json settings;                // what the runs were made with (split, bench), copied to the JSON
  SuiteBootstrapOptions bootstrap;
  std::vector<std::string> runs;          // finished runs, in run order
  std::vector<SuiteMethodSummary> methods;  // in the order given
  std::vector<SuiteWins> wins;            // every pair (i < j) in method order
  std::vector<std::pair<std::string, std::string>> failed;  // (run, error)

  nlohmann::json ToJson() const;   // suite_report.json
  std::string ToMarkdown() const;  // suite_report.md
};

// The mean of `values` (NaN left out) and its percentile interval from i.i.d. resamples of their
// indices, keyed by (options.seed, purpose, resample).
Interval BootstrapMeanInterval(const std::vector<double>& values, const SuiteBootstrapOptions& options,
                               const std::string& purpose);

// Ranks of `values` (1 = largest; equal values share the mean of their ranks; NaN ranks last,
// NaNs tied with each other).
std::vector<double> RanksDescending(const std::vector<double>& values);

// The summary of `runs` for `methods` (each finished run must hold every method's values).
SuiteSummary SummariseSuite(const std::string& name, const std::string& description,
                            const std::vector<std::string>& methods, const std::vector<SuiteRunResult>& runs,
                            const SuiteBootstrapOptions& options = {});

}  // namespace hoilcd
