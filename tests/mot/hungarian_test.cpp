#include "mot/hungarian.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <numeric>
#include <random>

namespace wardmap::mot {
namespace {

// Best total over all matchings of min(n, m) pairs, by enumerating permutations of the larger side.
double brute_full(const Eigen::MatrixXd& c) {
  const bool transpose = c.rows() > c.cols();
  const Eigen::MatrixXd a = transpose ? Eigen::MatrixXd(c.transpose()) : c;
  std::vector<int> perm(a.cols());
  std::iota(perm.begin(), perm.end(), 0);
  double best = std::numeric_limits<double>::infinity();
  do {
    double s = 0;
    for (int i = 0; i < a.rows(); ++i) s += a(i, perm[i]);
    best = std::min(best, s);
  } while (std::next_permutation(perm.begin(), perm.end()));
  return best;
}

// Best sum of (threshold - cost) over partial matchings using admissible pairs only (recursive).
double brute_thresholded(const Eigen::MatrixXd& c, double thr, int row, std::vector<char>& used) {
  if (row == c.rows()) return 0;
  double best = brute_thresholded(c, thr, row + 1, used);  // leave the row unassigned
  for (int j = 0; j < c.cols(); ++j) {
    if (used[j] || !std::isfinite(c(row, j)) || c(row, j) > thr) continue;
    used[j] = 1;
    best = std::max(best, thr - c(row, j) + brute_thresholded(c, thr, row + 1, used));
    used[j] = 0;
  }
  return best;
}

void expect_consistent(const Assignment& a, int n, int m) {
  ASSERT_EQ(static_cast<int>(a.row_to_col.size()), n);
  ASSERT_EQ(static_cast<int>(a.col_to_row.size()), m);
  for (const auto& [i, j] : a.matches) {
    EXPECT_EQ(a.row_to_col[i], j);
    EXPECT_EQ(a.col_to_row[j], i);
  }
  EXPECT_EQ(a.matches.size() + a.unmatched_rows.size(), static_cast<size_t>(n));
  EXPECT_EQ(a.matches.size() + a.unmatched_cols.size(), static_cast<size_t>(m));
}

TEST(Hungarian, KnownSquareCase) {
  Eigen::MatrixXd c(3, 3);
  c << 4, 1, 3,  //
      2, 0, 5,   //
      3, 2, 2;
  const Assignment a = solve_assignment(c);
  EXPECT_DOUBLE_EQ(a.total_cost, 5.0);  // (0,1) + (1,0) + (2,2)
  EXPECT_EQ(a.row_to_col, (std::vector<int>{1, 0, 2}));
}

TEST(Hungarian, MatchesBruteForceOnRandomRectangularMatrices) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> dim(1, 6);
  std::uniform_real_distribution<double> u(-3.0, 10.0);
  for (int trial = 0; trial < 400; ++trial) {
    const int n = dim(rng), m = dim(rng);
    Eigen::MatrixXd c(n, m);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < m; ++j) c(i, j) = (trial % 3 == 0) ? std::round(u(rng)) : u(rng);  // ties too
    const Assignment a = solve_assignment(c);
    expect_consistent(a, n, m);
    EXPECT_EQ(static_cast<int>(a.matches.size()), std::min(n, m));
    EXPECT_NEAR(a.total_cost, brute_full(c), 1e-9) << "trial " << trial;
  }
}

TEST(Hungarian, ThresholdedMatchesBruteForce) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> dim(0, 5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 400; ++trial) {
    const int n = dim(rng), m = dim(rng);
    const double thr = 0.2 + 0.6 * u(rng);
    Eigen::MatrixXd c(n, m);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < m; ++j) c(i, j) = u(rng) < 0.15 ? std::numeric_limits<double>::infinity() : u(rng);
    const Assignment a = solve_assignment(c, thr);
    expect_consistent(a, n, m);
    double gain = 0;
    for (const auto& [i, j] : a.matches) {
      EXPECT_LE(c(i, j), thr);
      gain += thr - c(i, j);
    }
    std::vector<char> used(m, 0);
    EXPECT_NEAR(gain, brute_thresholded(c, thr, 0, used), 1e-9) << "trial " << trial;
  }
}

TEST(Hungarian, ThresholdLeavesExpensivePairsUnassigned) {
  Eigen::MatrixXd c(2, 3);
  c << 0.1, 0.9, 0.8,  //
      0.95, 0.99, 0.3;
  const Assignment a = solve_assignment(c, 0.5);
  EXPECT_EQ(a.row_to_col, (std::vector<int>{0, 2}));
  const Assignment b = solve_assignment(c, 0.2);
  EXPECT_EQ(b.row_to_col, (std::vector<int>{0, -1}));
  EXPECT_EQ(b.unmatched_cols, (std::vector<int>{1, 2}));
}

TEST(Hungarian, InfiniteThresholdIsMaximumCardinalityOverFinitePairs) {
  const double inf = std::numeric_limits<double>::infinity();
  Eigen::MatrixXd c(2, 2);
  c << 1, 100,  //
      2, inf;
  const Assignment a = solve_assignment(c, inf);
  EXPECT_EQ(a.row_to_col, (std::vector<int>{1, 0}));
  EXPECT_THROW(solve_assignment(c), std::invalid_argument);
}

TEST(Hungarian, EmptyMatrices) {
  EXPECT_TRUE(solve_assignment(Eigen::MatrixXd(0, 3)).matches.empty());
  const Assignment a = solve_assignment(Eigen::MatrixXd(2, 0), 1.0);
  EXPECT_EQ(a.unmatched_rows.size(), 2u);
}

}  // namespace
}  // namespace wardmap::mot
