// Optimal rectangular assignment (Kuhn-Munkres with shortest augmenting paths, as in Jonker-Volgenant).
// Used by the tracker (Assoc. III-A.1) to match tracks (rows) to detections (columns).
#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

namespace wardmap::mot {

struct Assignment {
  std::vector<int> row_to_col;               // -1 when the row is unassigned
  std::vector<int> col_to_row;               // -1 when the column is unassigned
  std::vector<std::pair<int, int>> matches;  // (row, col), by increasing row
  std::vector<int> unmatched_rows, unmatched_cols;
  double total_cost = 0;  // sum of the matched costs
};

// Minimum-cost assignment of min(rows, cols) pairs. All costs must be finite (else std::invalid_argument).
Assignment solve_assignment(const Eigen::MatrixXd& cost);

// Thresholded assignment: pairs with cost > threshold (or a non-finite cost) are never matched, and
// the matching minimises  sum_matched cost + threshold / 2 * (#unmatched rows + #unmatched cols),
// i.e. it maximises sum_matched (threshold - cost): a pair is made only when it beats leaving both
// sides unassigned. This is the `lapjv(cost, cost_limit=threshold)` convention of FairMOT.
Assignment solve_assignment(const Eigen::MatrixXd& cost, double threshold);

}  // namespace wardmap::mot
