// Why the benchmark came out as it did, from its own numbers: whether the paper's finding holds
// (DLCD > SLCD, fusion >= the better), and each method's MRR on queries with and without HOI
// points, for report.md.
#pragma once

#include <string>

#include "hoilcd/bench/runner.h"

namespace hoilcd {

// Whether the paper's finding holds (DLCD > SLCD, fusion >= the better minus 0.01), in words.
std::string PaperFindingSummary(const BenchResult& result);

// report.md's "Diagnosis" section (empty without dlcd).
std::string DiagnosisMarkdown(const BenchResult& result);

}  // namespace hoilcd
