#include "mot/hungarian.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace wardmap::mot {
namespace {

// Rows <= cols, all costs finite. For each row, Dijkstra on reduced costs c(i,j) - u_i - v_j finds the
// cheapest augmenting path to a free column; column potentials v keep reduced costs non-negative and
// matched edges tight (u_i is implied: u_i = c(i, match_i) - v(match_i)).
std::vector<int> assign_rows_le_cols(const Eigen::MatrixXd& c) {
  const int n = static_cast<int>(c.rows()), m = static_cast<int>(c.cols());
  std::vector<double> v(m, 0.0), dist(m);
  std::vector<int> col_owner(m, -1), row_match(n, -1), prev_row(m), order;
  std::vector<char> done(m);
  order.reserve(m);
  for (int r = 0; r < n; ++r) {
    std::fill(done.begin(), done.end(), 0);
    order.clear();
    for (int j = 0; j < m; ++j) {
      dist[j] = c(r, j) - v[j];
      prev_row[j] = r;
    }
    int sink;
    for (;;) {
      int best = -1;
      for (int j = 0; j < m; ++j)
        if (!done[j] && (best < 0 || dist[j] < dist[best])) best = j;
      // Every column done without a free one: more rows than columns, which the callers rule out.
      if (best < 0) throw std::logic_error("assign_rows_le_cols: more rows than columns");
      done[best] = 1;
      order.push_back(best);
      const int i = col_owner[best];
      if (i < 0) {
        sink = best;
        break;
      }
      const double ui = c(i, best) - v[best];  // matched edge is tight
      for (int j = 0; j < m; ++j) {
        if (done[j]) continue;
        const double nd = dist[best] + c(i, j) - ui - v[j];
        if (nd < dist[j]) {
          dist[j] = nd;
          prev_row[j] = i;
        }
      }
    }
    const double delta = dist[sink];
    for (int j : order) v[j] -= delta - dist[j];
    // Augment: walk back from the sink flipping matched / unmatched edges.
    for (int j = sink;;) {
      const int i = prev_row[j];
      const int next = row_match[i];
      row_match[i] = j;
      col_owner[j] = i;
      if (i == r) break;
      j = next;
    }
  }
  return row_match;
}

Assignment make_result(const Eigen::MatrixXd& cost, std::vector<int> row_to_col) {
  Assignment a;
  a.row_to_col = std::move(row_to_col);
  a.col_to_row.assign(cost.cols(), -1);
  for (int i = 0; i < static_cast<int>(cost.rows()); ++i) {
    const int j = a.row_to_col[i];
    if (j < 0) {
      a.unmatched_rows.push_back(i);
      continue;
    }
    a.col_to_row[j] = i;
    a.matches.emplace_back(i, j);
    a.total_cost += cost(i, j);
  }
  for (int j = 0; j < static_cast<int>(cost.cols()); ++j)
    if (a.col_to_row[j] < 0) a.unmatched_cols.push_back(j);
  return a;
}

}  // namespace

Assignment solve_assignment(const Eigen::MatrixXd& cost) {
  if (!cost.allFinite())
    throw std::invalid_argument("solve_assignment: costs must be finite (use the thresholded form)");
  const int n = static_cast<int>(cost.rows()), m = static_cast<int>(cost.cols());
  if (n == 0 || m == 0) return make_result(cost, std::vector<int>(n, -1));
  if (n <= m) return make_result(cost, assign_rows_le_cols(cost));
  const std::vector<int> col_to_row = assign_rows_le_cols(cost.transpose());
  std::vector<int> row_to_col(n, -1);
  for (int j = 0; j < m; ++j) row_to_col[col_to_row[j]] = j;
  return make_result(cost, std::move(row_to_col));
}

Assignment solve_assignment(const Eigen::MatrixXd& cost, double threshold) {
  const int n = static_cast<int>(cost.rows()), m = static_cast<int>(cost.cols());
  if (std::isnan(threshold)) throw std::invalid_argument("solve_assignment: threshold is NaN");
  if (n == 0 || m == 0) return make_result(cost, std::vector<int>(n, -1));
  if (std::isinf(threshold) && threshold > 0) {
    // Every finite pair is admissible: a plain assignment, then drop the forbidden pairs.
    Eigen::MatrixXd c = cost;
    double hi = 0;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < m; ++j)
        if (std::isfinite(c(i, j))) hi = std::max(hi, std::abs(c(i, j)));
    const double big = 2.0 * (n + m) * (hi + 1);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < m; ++j)
        if (!std::isfinite(c(i, j))) c(i, j) = big;
    Assignment a = solve_assignment(c);
    std::vector<int> r2c = a.row_to_col;
    for (int i = 0; i < n; ++i)
      if (r2c[i] >= 0 && !std::isfinite(cost(i, r2c[i]))) r2c[i] = -1;
    return make_result(cost, std::move(r2c));
  }
  // Square (n + m) problem: real rows may take a dummy column (row unassigned, cost threshold / 2),
  // dummy rows take the real columns left over (cost threshold / 2) or a dummy column (cost 0).
  double lo = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j)
      if (std::isfinite(cost(i, j))) lo = std::min(lo, cost(i, j));
  const double half = 0.5 * threshold;
  const double big = (n + m) * (std::abs(half) + std::abs(lo) + 1.0) + std::abs(threshold) + 1.0;
  const int N = n + m;
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(N, N);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) c(i, j) = (std::isfinite(cost(i, j)) && cost(i, j) <= threshold) ? cost(i, j) : big;
  c.topRightCorner(n, n).setConstant(half);
  c.bottomLeftCorner(m, m).setConstant(half);
  const std::vector<int> full = assign_rows_le_cols(c);
  std::vector<int> r2c(n, -1);
  for (int i = 0; i < n; ++i)
    if (full[i] < m && c(i, full[i]) < big) r2c[i] = full[i];
  return make_result(cost, std::move(r2c));
}

}  // namespace wardmap::mot
