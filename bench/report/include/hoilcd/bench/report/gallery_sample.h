// Which queries report.html's gallery shows: a deterministic sample, at most a fixed number per
// method, stratum and outcome, so a long sequence's page stays small while every kind of query
// (each stratum, hits and misses of each method, blank views) keeps its examples.
#pragma once

#include <string>
#include <vector>

#include "hoilcd/bench/evaluation/metrics.h"
#include "hoilcd/bench/evaluation/query_conditions.h"

namespace hoilcd {

// Queries drawn per group (docs/guide/report.md): enough to compare two examples, few enough that
// paper_room's page stays far under its 30 MB budget.
constexpr int kGalleryPerGroup = 2;

// The query's outcome under a method: "hit" when its top-1 is a true match, "miss" otherwise;
// "" when it is not scored (no true match in its database).
std::string GalleryOutcome(const QueryRecord& record);

// The groups: for every method and outcome (hit, miss), the scored queries of that method with
// that outcome, all of them and those of each stratum (each stratification's, and "blank view"
// whatever the stratifications). From each group, in query (time) order, `per_group` queries at evenly
// spaced positions ((2k+1)·n / (2·per_group), k < per_group; all of them when n <= per_group).
// Returns the union as query indices, ascending. `records`: per method, parallel to `conditions`.
std::vector<size_t> SampleGallery(const std::vector<const std::vector<QueryRecord>*>& records,
                                  const std::vector<QueryConditions>& conditions,
                                  const std::vector<std::string>& stratifications, int per_group = kGalleryPerGroup);

// The stratifications of a report's strata rows, in their order (each once).
std::vector<std::string> StratificationsOf(const std::vector<StratumRow>& strata);

}  // namespace hoilcd
