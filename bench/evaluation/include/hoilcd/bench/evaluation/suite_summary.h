// The summary of a benchmark suite (`hoilcd suite`): per method, each run's MRR and R@1 and each
// sequence's mean over its seeds; the mean over sequences with a percentile bootstrap interval
// (resampling sequences: the seeds of one room are not independent of each other), each method's
// rank per sequence and mean rank, and paired wins per sequence for every pair of methods. Built from numbers alone, so
// it is tested on constructed values; the pipeline (suite.h) fills it from the runs' report.json files.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hoilcd/bench/evaluation/bootstrap.h"

namespace hoilcd {

// One (sequence, seed) of a suite: its metrics per method, or the error that stopped it.
struct SuiteRunResult {
  std::string name;                           // "<sequence>-seed<S>": the run's identity
  std::string error;                          // empty when the run finished
  std::map<std::string, double> mrr;          // method -> MRR (NaN: no scored query)
  std::map<std::string, double> recall_at_1;  // method -> R@1
  std::string sequence;                       // the sequence it is a seed of (empty: its own)
  bool ok() const { return error.empty(); }
};

// The interval over sequences: each sequence's mean over its seeds, the sequences resampled i.i.d.
// (independent rooms, where the seeds of one room share its layout), keyed by (seed, resample).
struct SuiteBootstrapOptions {
  int resamples = 2000;      // bootstrap resamples
  double confidence = 0.95;  // of the two-sided percentile interval
  uint64_t seed = 1;         // of the resampling: fixed, so a report is byte-reproducible
};

// One method over the finished runs.
struct SuiteMethodSummary {
  std::string method;
  std::vector<double> mrr, recall_at_1;  // per finished run, in run order
  std::vector<double> rank;              // per finished run: 1 = best MRR, ties share the mean rank
  // Per sequence with a finished run (SuiteSummary::sequences): the mean over its finished runs
  // (NaN: none scored), and the rank of that mean.
  std::vector<double> sequence_mrr, sequence_recall_at_1, sequence_rank;
  double mean_mrr = NAN, mean_recall_at_1 = NAN, mean_rank = NAN;  // over sequences
  Interval mrr_interval, recall_at_1_interval;                     // of the means
};

// How often `a` beat `b` on a sequence's mean MRR.
struct SuiteWins {
  std::string a, b;
  int a_wins = 0, b_wins = 0, ties = 0;
  std::string ToString() const;  // "slcd beats dlcd on 9 of 12 (2 ties)"
};

struct SuiteSummary {
  std::string name, description;
  nlohmann::json settings;  // what the runs were made with (split, bench), copied to the JSON
  SuiteBootstrapOptions bootstrap;
  std::vector<std::string> runs;                            // finished runs, in run order
  std::vector<std::string> sequences;                       // their sequences, in order of first appearance
  std::vector<SuiteMethodSummary> methods;                  // in the order given
  std::vector<SuiteWins> wins;                              // every pair (i < j) in method order
  std::vector<std::pair<std::string, std::string>> failed;  // (run, error)
  // Finished run -> its report folder, for suite_report.html's links; not in the JSON or Markdown,
  // which stay the same bytes however the runs were sharded.
  std::map<std::string, std::string> run_dirs;

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
