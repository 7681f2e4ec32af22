// Linear assignment (rectangular, with a cost limit) by the Jonker-Volgenant algorithm, as
// ByteTrack calls it through lap.lapjv(cost, extend_cost=True, cost_limit=thresh).
#pragma once

#include <utility>
#include <vector>

namespace hoilcd {

struct Assignment {
  std::vector<std::pair<int, int>> matches;  // (row, col), sorted by row
  std::vector<int> unmatched_rows;           // ascending
  std::vector<int> unmatched_cols;           // ascending
};

// Solves min over partial matchings of  sum(cost of matched pairs) + cost_limit/2 per unmatched
// row and per unmatched column, which is what lap.lapjv does by extending the R x C matrix to a
// square (R+C) matrix filled with cost_limit/2 (and 0 in the dummy-dummy block). A pair costing
// more than cost_limit is therefore never matched. With cost_limit = +infinity the result is a
// full assignment of min(R, C) pairs. `cost` is row-major, every row the same length, finite.
// Hand-written because OpenCV (and the other Debian libraries we use) has no linear assignment.
Assignment LinearAssignment(const std::vector<std::vector<double>>& cost, double cost_limit);

// Square assignment: returns col_of_row (a permutation) minimising the total cost.
// `cost` is n x n row-major. Exposed for tests.
std::vector<int> SolveSquareAssignment(const std::vector<double>& cost, int n);

}  // namespace hoilcd
