// What each query frame shows and how it was taken, from the dataset's ground truth (persons.json,
// the EXR's true temperature and class channels, events.json, poses.csv), and the metrics of
// every method per stratum of those conditions: a blank wall, static structure only, a few people
// or a crowd; how occluded the people are; whether someone walks through. A stratum also states
// what a random order would score there (chance), so a user sees where every method is guessing.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hoilcd/bench/evaluation/metrics.h"
#include "hoilcd/bench/evaluation/protocol.h"
#include "hoilcd/core/dataset/dataset.h"

namespace hoilcd {

// A blank view: the true temperature spreads less than this across the frame (2nd to 98th
// percentile), with no person and nothing but walls, floor and ceiling in view.
constexpr double kBlankSpreadK = 0.5;
// A pixel of static structure with contrast: not a person, and its true temperature differs from
// a 4-neighbour's by at least this.
constexpr double kContrastK = 0.2;

struct QueryConditions {
  int frame = 0;
  int lap = 0;
  int people_in_view = 0;       // persons.json: visible fraction above 0
  int walkers_in_view = 0;      // of them, not seated
  double mean_occlusion = NAN;  // mean occlusion fraction of the people in view (NaN: none)
  // From the EXR (NaN or -1 when the dataset has no EXRs):
  int person_pixels = -1;                    // pixels of class person
  double temperature_spread_k = NAN;         // T_true, 98th minus 2nd percentile
  bool structure_only_classes = false;       // nothing but wall, floor, ceiling (and no person)
  int structure_contrast_pixels = -1;        // non-person pixels with a 4-neighbour kContrastK apart
  double structure_contrast_fraction = NAN;  // of them, as a fraction of the frame's pixels
  bool blank = false;                        // spread < kBlankSpreadK and structure_only_classes
  bool ffc_or_frozen = false;                // an FFC at this frame, or a frame repeating an earlier one
  double turn_rate_deg_s = NAN;              // |heading change| of the true base pose per second
  double nearest_true_distance_m = NAN;      // to the nearest true match in its database (true poses)
  double nearest_true_heading_deg = NAN;     // |heading difference| to that match
};

// The EXR-based fields of frame `frame` (person pixels, temperature spread, structure only,
// contrast, blank), the rest left as constructed. InputError when the dataset has no EXRs.
QueryConditions ImageConditionsOf(const Dataset& dataset, int frame);

// One condition per query, in query order; EXR-based fields only when the dataset has EXRs.
// `threads`: 0 = every CPU.
std::vector<QueryConditions> ComputeQueryConditions(const Dataset& dataset, const std::vector<Query>& queries,
                                                    int threads = 0);

// queries.csv's extra columns: header (starting with ',') and one row per condition.
std::string ConditionsCsvHeader();
std::string ConditionsCsvRow(const QueryConditions& c);

// The stratifications the report can split by (--strata): their names and their strata.
// "view", "contrast", "occlusion", "walkers", "turning", "lap", "ffc"
std::vector<std::string> StratificationNames();
std::vector<std::string> DefaultStratifications();  // "view", "contrast", "occlusion", "walkers"
// The stratum of `c` under `stratification` ("" when the query belongs to none, e.g. occlusion
// with nobody in view).
std::string StratumOf(const std::string& stratification, const QueryConditions& c);

struct StratumRow {
  std::string stratification, stratum;
  int queries = 0;          // scored queries in the stratum
  double chance_mrr = NAN;  // the MRR of a uniformly random order of each database
  std::vector<std::string> methods;
  std::vector<double> mrr, recall_at_1;  // per method, parallel to methods
};

// The expected reciprocal rank of the first true match when `database_size` items, `true_matches`
// of them true, are put in a uniformly random order.
double ChanceReciprocalRank(int database_size, int true_matches);

// Every stratum of each stratification, in a fixed order, for the methods' records (each a
// MethodMetrics::queries, parallel to `conditions`).
std::vector<StratumRow> Stratify(const std::vector<QueryConditions>& conditions, const std::vector<std::string>& names,
                                 const std::vector<const std::vector<QueryRecord>*>& records,
                                 const std::vector<std::string>& stratifications);

nlohmann::json StrataJson(const std::vector<StratumRow>& rows);

}  // namespace hoilcd
