#include "hoilcd/core/tracking/lapjv.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>

#include <gtest/gtest.h>

#include "hoilcd/core/util/random.h"

namespace hoilcd {
namespace {

using Matrix = std::vector<std::vector<double>>;

// Objective lap.lapjv(extend_cost=True, cost_limit) minimises: matched costs plus limit/2 for
// every unmatched row and every unmatched column.
double Objective(const Matrix& cost, double limit, const Assignment& a) {
  double total = 0;
  for (const auto& [i, j] : a.matches) total += cost[i][j];
  total += limit / 2 * static_cast<double>(a.unmatched_rows.size() + a.unmatched_cols.size());
  return total;
}

// Brute force over every partial matching (each row takes an unused column or none).
double BruteForceObjective(const Matrix& cost, double limit) {
  const int rows = static_cast<int>(cost.size());
  const int cols = static_cast<int>(cost[0].size());
  std::vector<char> used(cols, 0);
  std::function<double(int, int)> best = [&](int row, int matched) -> double {
    if (row == rows) return limit / 2 * ((rows - matched) + (cols - matched));
    double result = best(row + 1, matched);  // row left unmatched
    for (int j = 0; j < cols; ++j) {
      if (used[j]) continue;
      used[j] = 1;
      result = std::min(result, cost[row][j] + best(row + 1, matched + 1));
      used[j] = 0;
    }
    return result;
  };
  return best(0, 0);
}

// Brute force over full assignments of min(R, C) pairs (no limit).
double BruteForceFull(const Matrix& cost) {
  const int rows = static_cast<int>(cost.size());
  const int cols = static_cast<int>(cost[0].size());
  const bool transpose = rows > cols;
  const int small = std::min(rows, cols), large = std::max(rows, cols);
  std::vector<int> perm(large);
  std::iota(perm.begin(), perm.end(), 0);
  double best = std::numeric_limits<double>::infinity();
  do {
    double total = 0;
    for (int k = 0; k < small; ++k) total += transpose ? cost[perm[k]][k] : cost[k][perm[k]];
    best = std::min(best, total);
  } while (std::next_permutation(perm.begin(), perm.end()));
  return best;
}

Matrix RandomMatrix(int rows, int cols, int trial, bool with_ties) {
  Rng rng = KeyedRng(7, "test.lapjv", rows, cols, trial);
  Matrix m(rows, std::vector<double>(cols));
  for (auto& row : m) {
    for (double& x : row) {
      x = with_ties ? static_cast<double>(rng.UniformInt(4)) / 4 : rng.Uniform();
    }
  }
  return m;
}

void ExpectConsistent(const Assignment& a, int rows, int cols) {
  std::vector<int> row_seen(rows, 0), col_seen(cols, 0);
  for (const auto& [i, j] : a.matches) {
    ++row_seen[i];
    ++col_seen[j];
  }
  for (int i : a.unmatched_rows) ++row_seen[i];
  for (int j : a.unmatched_cols) ++col_seen[j];
  for (int i = 0; i < rows; ++i) EXPECT_EQ(row_seen[i], 1) << "row " << i;
  for (int j = 0; j < cols; ++j) EXPECT_EQ(col_seen[j], 1) << "col " << j;
}

TEST(LinearAssignment, SquareSolverMatchesBruteForceOnRandomMatrices) {
  for (int n = 1; n <= 6; ++n) {
    for (int trial = 0; trial < 30; ++trial) {
      for (bool ties : {false, true}) {
        const Matrix m = RandomMatrix(n, n, trial, ties);
        std::vector<double> flat;
        for (const auto& row : m) flat.insert(flat.end(), row.begin(), row.end());
        const std::vector<int> col_of_row = SolveSquareAssignment(flat, n);
        std::vector<int> sorted = col_of_row;
        std::sort(sorted.begin(), sorted.end());
        for (int k = 0; k < n; ++k) ASSERT_EQ(sorted[k], k);
        double total = 0;
        for (int i = 0; i < n; ++i) total += m[i][col_of_row[i]];
        EXPECT_NEAR(total, BruteForceFull(m), 1e-12) << "n=" << n << " trial=" << trial;
      }
    }
  }
}

TEST(LinearAssignment, RectangularWithCostLimitMatchesBruteForce) {
  for (int rows = 1; rows <= 5; ++rows) {
    for (int cols = 1; cols <= 5; ++cols) {
      for (int trial = 0; trial < 20; ++trial) {
        const Matrix m = RandomMatrix(rows, cols, trial, trial % 2 == 1);
        for (double limit : {0.2, 0.5, 0.8, 1.5}) {
          const Assignment a = LinearAssignment(m, limit);
          ExpectConsistent(a, rows, cols);
          EXPECT_NEAR(Objective(m, limit, a), BruteForceObjective(m, limit), 1e-12)
              << rows << "x" << cols << " trial=" << trial << " limit=" << limit;
          for (const auto& [i, j] : a.matches) EXPECT_LE(m[i][j], limit);
        }
      }
    }
  }
}

TEST(LinearAssignment, WithoutLimitMatchesMinOfRowsAndColsAtBruteForceCost) {
  const double inf = std::numeric_limits<double>::infinity();
  for (int rows = 1; rows <= 5; ++rows) {
    for (int cols = 1; cols <= 5; ++cols) {
      for (int trial = 0; trial < 10; ++trial) {
        const Matrix m = RandomMatrix(rows, cols, 100 + trial, false);
        const Assignment a = LinearAssignment(m, inf);
        ExpectConsistent(a, rows, cols);
        ASSERT_EQ(static_cast<int>(a.matches.size()), std::min(rows, cols));
        double total = 0;
        for (const auto& [i, j] : a.matches) total += m[i][j];
        EXPECT_NEAR(total, BruteForceFull(m), 1e-12);
      }
    }
  }
}

TEST(LinearAssignment, PairsAboveTheLimitStayUnmatched) {
  const Matrix m = {{0.1, 0.9}, {0.95, 0.85}};
  const Assignment a = LinearAssignment(m, 0.8);
  ASSERT_EQ(a.matches.size(), 1u);
  EXPECT_EQ(a.matches[0], std::make_pair(0, 0));
  EXPECT_EQ(a.unmatched_rows, std::vector<int>{1});
  EXPECT_EQ(a.unmatched_cols, std::vector<int>{1});
}

TEST(LinearAssignment, EmptyMatrixLeavesEverythingUnmatched) {
  const Assignment no_cols = LinearAssignment(Matrix(3), 0.8);
  EXPECT_TRUE(no_cols.matches.empty());
  EXPECT_EQ(no_cols.unmatched_rows, (std::vector<int>{0, 1, 2}));
  EXPECT_TRUE(LinearAssignment(Matrix(), 0.8).unmatched_rows.empty());
}

TEST(LinearAssignment, RaggedMatrixIsRejected) {
  EXPECT_THROW(LinearAssignment({{0.1, 0.2}, {0.3}}, 0.8), std::logic_error);
}

}  // namespace
}  // namespace hoilcd
