#include "hoilcd/core/tracking/lapjv.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "hoilcd/core/util/error.h"

namespace hoilcd {

namespace {

// Jonker & Volgenant (1987) on an n x n row-major cost matrix: the assignment so far and the
// column potentials (row potentials stay implicit), changed phase by phase.
class JonkerVolgenant {
 public:
  JonkerVolgenant(const std::vector<double>& cost, int n)
      : cost_(cost), n_(n), col_of_row_(n, -1), row_of_col_(n, -1), v_(n, 0.0), dist_(n), pred_(n), scanned_(n) {}

  std::vector<int> Solve() {
    ReduceColumns();
    for (int free_row : TransferReduction()) Augment(free_row);
    return col_of_row_;
  }

 private:
  double c(int i, int j) const { return cost_[static_cast<size_t>(i) * n_ + j]; }

  // Column reduction: v[j] = column minimum; a row keeps the first column it is the minimum of.
  void ReduceColumns() {
    for (int j = n_ - 1; j >= 0; --j) {
      int i_min = 0;
      for (int i = 1; i < n_; ++i) {
        if (c(i, j) < c(i_min, j)) i_min = i;
      }
      v_[j] = c(i_min, j);
      if (col_of_row_[i_min] < 0) {
        col_of_row_[i_min] = j;
        row_of_col_[j] = i_min;
      }
    }
  }

  // Reduction transfer: lower the potential of each kept column so its row sees its second-best
  // reduced cost there. Keeps every assigned column a row minimum. Returns the free rows.
  std::vector<int> TransferReduction() {
    std::vector<int> free_rows;
    for (int i = 0; i < n_; ++i) {
      const int j1 = col_of_row_[i];
      if (j1 < 0) {
        free_rows.push_back(i);
        continue;
      }
      double second = std::numeric_limits<double>::infinity();
      for (int j = 0; j < n_; ++j) {
        if (j != j1) second = std::min(second, c(i, j) - v_[j]);
      }
      if (std::isfinite(second)) v_[j1] = c(i, j1) - second;
    }
    return free_rows;
  }

  // Augmentation: a shortest path (Dijkstra on reduced costs) from a free row to a free column,
  // then the assignment flipped along it.
  void Augment(int free_row) {
    for (int j = 0; j < n_; ++j) {
      dist_[j] = c(free_row, j) - v_[j];
      pred_[j] = free_row;
      scanned_[j] = 0;
    }
    scanned_cols_.clear();
    int sink = -1;
    double mu = 0;
    while (sink < 0) {
      int j_min = -1;
      for (int j = 0; j < n_; ++j) {
        if (scanned_[j]) continue;
        // Ties go to a free column: the path ends sooner at the same length.
        if (j_min < 0 || dist_[j] < dist_[j_min] ||
            (dist_[j] == dist_[j_min] && row_of_col_[j] < 0 && row_of_col_[j_min] >= 0)) {
          j_min = j;
        }
      }
      mu = dist_[j_min];
      if (row_of_col_[j_min] < 0) {
        sink = j_min;
        break;
      }
      scanned_[j_min] = 1;
      scanned_cols_.push_back(j_min);
      const int i = row_of_col_[j_min];
      const double u_i = c(i, j_min) - v_[j_min];
      for (int j = 0; j < n_; ++j) {
        if (scanned_[j]) continue;
        const double d = mu + c(i, j) - v_[j] - u_i;
        if (d < dist_[j]) {
          dist_[j] = d;
          pred_[j] = i;
        }
      }
    }
    for (int j : scanned_cols_) v_[j] += dist_[j] - mu;
    for (int j = sink;;) {
      const int i = pred_[j];
      row_of_col_[j] = i;
      const int previous = col_of_row_[i];
      col_of_row_[i] = j;
      if (i == free_row) break;
      j = previous;
    }
  }

  const std::vector<double>& cost_;
  const int n_;
  std::vector<int> col_of_row_, row_of_col_;
  std::vector<double> v_;  // column potentials
  // Scratch of Augment.
  std::vector<double> dist_;
  std::vector<int> pred_;
  std::vector<char> scanned_;
  std::vector<int> scanned_cols_;
};

}  // namespace

// Jonker & Volgenant (1987): column reduction, reduction transfer, then one shortest augmenting
// path (Dijkstra on reduced costs) per free row. JV's augmenting row reduction phase is left
// out: it only speeds up large problems and ours are a few tracks by a few detections.
std::vector<int> SolveSquareAssignment(const std::vector<double>& cost, int n) {
  HOILCD_CHECK(n >= 0);
  HOILCD_CHECK(cost.size() == static_cast<size_t>(n) * static_cast<size_t>(n));
  return JonkerVolgenant(cost, n).Solve();
}

Assignment LinearAssignment(const std::vector<std::vector<double>>& cost, double cost_limit) {
  HOILCD_CHECK_MSG(!std::isnan(cost_limit) && cost_limit >= 0, "cost_limit " << cost_limit);
  const int rows = static_cast<int>(cost.size());
  const int cols = rows > 0 ? static_cast<int>(cost[0].size()) : 0;
  for (const auto& row : cost) HOILCD_CHECK(static_cast<int>(row.size()) == cols);
  Assignment result;
  if (rows == 0 || cols == 0) {
    for (int i = 0; i < rows; ++i) result.unmatched_rows.push_back(i);
    for (int j = 0; j < cols; ++j) result.unmatched_cols.push_back(j);
    return result;
  }
  // Square extension as lap.lapjv(extend_cost=True): with a finite limit, (R+C) x (R+C) where a
  // real row may take a dummy column (and a real column a dummy row) for cost_limit/2 each;
  // without a limit, zero padding to max(R, C).
  const bool limited = std::isfinite(cost_limit);
  const int n = limited ? rows + cols : std::max(rows, cols);
  const double pad = limited ? cost_limit / 2 : 0.0;
  std::vector<double> square(static_cast<size_t>(n) * n, pad);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      double& entry = square[static_cast<size_t>(i) * n + j];
      if (i < rows && j < cols) {
        HOILCD_CHECK_MSG(std::isfinite(cost[i][j]), "cost[" << i << "][" << j << "]");
        entry = cost[i][j];
      } else if (i >= rows && j >= cols) {
        entry = 0.0;
      }
    }
  }
  const std::vector<int> col_of_row = SolveSquareAssignment(square, n);
  std::vector<char> col_matched(cols, 0);
  for (int i = 0; i < rows; ++i) {
    const int j = col_of_row[i];
    if (j < cols) {
      result.matches.emplace_back(i, j);
      col_matched[j] = 1;
    } else {
      result.unmatched_rows.push_back(i);
    }
  }
  for (int j = 0; j < cols; ++j) {
    if (!col_matched[j]) result.unmatched_cols.push_back(j);
  }
  return result;
}

}  // namespace hoilcd
