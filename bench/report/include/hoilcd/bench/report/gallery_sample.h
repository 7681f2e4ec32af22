// Which queries report.html's gallery shows: a deterministic sample, at most a fixed number per
// method, stratum and outcome, spread out in time, so a long sequence's page stays small while
// every kind of query (each stratum, hits and misses of each method, blank views) keeps its
// examples and no two entries show nearly the same frame.
#pragma once

#include <string>
#include <vector>

#include "hoilcd/bench/evaluation/metrics.h"
#include "hoilcd/bench/evaluation/query_conditions.h"

namespace hoilcd {

// Queries drawn per group (docs/guide/report.md): enough to compare two examples, few enough that
// paper_room's page stays far under its 30 MB budget.
constexpr int kGalleryPerGroup = 2;
// Frames between any two sampled queries, at least: at paper_room's 25 Hz and 0.4 m/s, 0.5 s and
// 0.2 m (the paper's true-match radius), so no two entries show one place from nearly one pose.
constexpr int kGalleryMinGapFrames = 12;

// How many queries the gallery takes per group and how far apart.
struct GallerySampling {
  int per_group = kGalleryPerGroup;           // queries per method, outcome and stratum
  int min_gap_frames = kGalleryMinGapFrames;  // frames, at least, between two sampled queries (1: any)
};

// The query's outcome under a method: "hit" when its top-1 is a true match, "miss" otherwise;
// "" when it is not scored (no true match in its database).
std::string GalleryOutcome(const QueryRecord& record);

// The groups: for every method and outcome (hit, miss), the scored queries of that method with
// that outcome, all of them and those of each stratum (each stratification's, and "blank view"
// whatever the stratifications). The groups pick in order of size, smallest first (ties: method,
// outcome, stratum), so a rare kind of query is taken before common ones crowd it out. A group
// in query (time) order is cut into per_group equal slots; for each slot that holds no sampled
// query yet, it takes the query nearest the slot's middle that is at least min_gap_frames from
// every sampled query, until it holds per_group sampled queries (all of them when it has fewer).
// So no two sampled queries are closer than min_gap_frames, and a group holds fewer than
// min(per_group, its size) only when each of its other queries lies within the gap of a sampled
// one. Returns the sample as query indices, ascending. `records`: per method, parallel to
// `conditions` (whose frame fields give the gap).
std::vector<size_t> SampleGallery(const std::vector<const std::vector<QueryRecord>*>& records,
                                  const std::vector<QueryConditions>& conditions,
                                  const std::vector<std::string>& stratifications,
                                  const GallerySampling& sampling = GallerySampling());

// The stratifications of a report's strata rows, in their order (each once).
std::vector<std::string> StratificationsOf(const std::vector<StratumRow>& strata);

}  // namespace hoilcd
