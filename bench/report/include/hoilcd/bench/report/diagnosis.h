// Why the benchmark came out as it did, from its own numbers: whether the paper's finding holds
// (DLCD > SLCD, fusion >= the better), each method's MRR on queries with and without HOI points,
// where fusion loses to the better of SLCD and DLCD, and what the oracles (dlcd-oracle,
// slcd-ideal) isolate. report.md prints it as prose and tables; report.json holds the same
// numbers under "diagnosis".
#pragma once

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hoilcd/bench/runner/runner.h"

namespace hoilcd {

// Whether the paper's finding holds (DLCD > SLCD, fusion >= the better minus 0.01), in words.
std::string PaperFindingSummary(const BenchResult& result);

struct MethodDiagnosis {
  std::string method;
  double mrr_with_hoi = NAN;     // MRR over the scored queries whose frame has HOI points
  double mrr_without_hoi = NAN;  // MRR over the scored queries whose frame has none
};

// Fusion against the better of slcd and dlcd, query by query (scored queries).
struct FusionDiagnosis {
  std::string better;                              // the one of slcd, dlcd with the higher MRR (slcd on a tie)
  std::string weaker;                              // the other one
  int queries_ranked_lower = 0;                    // fusion ranks the true match lower than `better` does
  int queries_ranked_lower_weaker_top1_false = 0;  // ... and `weaker`'s top-1 is a false match
  int queries_ranked_higher = 0;                   // fusion ranks the true match higher than `better` does
};

// An oracle against the method whose part it replaces with ground truth: dlcd-oracle (the true
// people) against dlcd, slcd-ideal (the noise-free image) against slcd.
struct OracleDiagnosis {
  std::string oracle;  // "dlcd-oracle" | "slcd-ideal"
  std::string method;  // "dlcd" | "slcd"
  double oracle_mrr = NAN;
  double method_mrr = NAN;  // NaN when the method did not run
  double delta = NAN;       // oracle_mrr - method_mrr
  Interval interval;        // of delta: the paired bootstrap's (NaN ends when not computed)
  bool helps = false;       // the oracle is better beyond the noise: the replaced part costs the method
  std::string finding;      // what the numbers show, in words
};

struct Diagnosis {
  bool evaluated = false;                 // something to diagnose: dlcd ran, an oracle ran or was left out
  bool hoi_split = false;                 // dlcd ran: the HOI split below is filled
  int queries_with_hoi = 0;               // scored queries whose frame has HOI points (people detected)
  int queries_without_hoi = 0;            // scored queries whose frame has none
  std::vector<MethodDiagnosis> methods;   // every method run, in run order
  std::optional<FusionDiagnosis> fusion;  // set when slcd, dlcd and fusion ran
  std::vector<OracleDiagnosis> oracles;   // every oracle that ran, in run order
  std::vector<std::string> not_run;       // optional methods left out (BenchResult::skipped)

  // report.json's "diagnosis" (non-finite MRRs as null).
  nlohmann::json ToJson() const;
};

Diagnosis Diagnose(const BenchResult& result);

// report.md's "Diagnosis" section (empty when !diagnosis.evaluated).
std::string DiagnosisMarkdown(const BenchResult& result, const Diagnosis& diagnosis);

}  // namespace hoilcd
