// Why the benchmark came out as it did, from its own numbers: whether the paper's finding holds
// (DLCD > SLCD, fusion >= the better), each method's MRR on queries with and without HOI points,
// and where fusion loses to the better of SLCD and DLCD. report.md prints it as prose and a
// table; report.json holds the same numbers under "diagnosis".
#pragma once

#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

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
  std::string better;            // the one of slcd, dlcd with the higher MRR (slcd on a tie)
  std::string weaker;            // the other one
  int queries_ranked_lower = 0;  // fusion ranks the true match lower than `better` does
  int queries_ranked_lower_weaker_top1_false = 0;  // ... and `weaker`'s top-1 is a false match
  int queries_ranked_higher = 0;  // fusion ranks the true match higher than `better` does
};

struct Diagnosis {
  bool evaluated = false;       // dlcd ran (nothing to diagnose without it)
  int queries_with_hoi = 0;     // scored queries whose frame has HOI points (people detected)
  int queries_without_hoi = 0;  // scored queries whose frame has none
  std::vector<MethodDiagnosis> methods;  // every method run, in run order
  std::optional<FusionDiagnosis> fusion;  // set when slcd, dlcd and fusion ran

  // report.json's "diagnosis" (non-finite MRRs as null).
  nlohmann::json ToJson() const;
};

Diagnosis Diagnose(const BenchResult& result);

// report.md's "Diagnosis" section (empty when !diagnosis.evaluated).
std::string DiagnosisMarkdown(const BenchResult& result, const Diagnosis& diagnosis);

}  // namespace hoilcd
