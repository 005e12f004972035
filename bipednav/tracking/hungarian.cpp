#include "bipednav/tracking/hungarian.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "bipednav/common/error.hpp"

namespace bipednav::tracking {

namespace {

// Rows to columns for a finite n x m matrix with n <= m: every row gets a column. The dual
// potentials u (rows), v (columns) keep a[i][j] - u[i] - v[j] >= 0, tight on the matching; each
// row is added by a Dijkstra-like search for the cheapest augmenting path in reduced costs.
std::vector<int> assign_rows(const Eigen::MatrixXd& a) {
  const auto n = static_cast<int>(a.rows()), m = static_cast<int>(a.cols());
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // 1-based: index 0 is the virtual column the augmenting path starts from.
  std::vector<double> u(n + 1, 0.0), v(m + 1, 0.0), min_reduced(m + 1);
  std::vector<int> row_of(m + 1, 0), way(m + 1, 0);
  std::vector<char> used(m + 1);
  for (int i = 1; i <= n; ++i) {
    row_of[0] = i;
    int j0 = 0;
    std::fill(min_reduced.begin(), min_reduced.end(), kInf);
    std::fill(used.begin(), used.end(), 0);
    do {
      used[j0] = 1;
      const int i0 = row_of[j0];
      double delta = kInf;
      int j1 = 0;
      for (int j = 1; j <= m; ++j) {
        if (used[j]) continue;
        const double reduced = a(i0 - 1, j - 1) - u[i0] - v[j];
        if (reduced < min_reduced[j]) min_reduced[j] = reduced, way[j] = j0;
        if (min_reduced[j] < delta) delta = min_reduced[j], j1 = j;
      }
      for (int j = 0; j <= m; ++j) {
        if (used[j]) {
          u[row_of[j]] += delta;
          v[j] -= delta;
        } else {
          min_reduced[j] -= delta;
        }
      }
      j0 = j1;
    } while (row_of[j0] != 0);
    do {  // flip the path's matched and unmatched edges
      const int j1 = way[j0];
      row_of[j0] = row_of[j1];
      j0 = j1;
    } while (j0 != 0);
  }
  std::vector<int> col_of(n, -1);
  for (int j = 1; j <= m; ++j)
    if (row_of[j] != 0) col_of[row_of[j] - 1] = j - 1;
  return col_of;
}

}  // namespace

std::vector<int> solve_assignment(const Eigen::MatrixXd& cost) {
  const auto n = static_cast<int>(cost.rows()), m = static_cast<int>(cost.cols());
  if (n == 0 || m == 0) return std::vector<int>(n, -1);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      const double c = cost(i, j);
      if (std::isnan(c) || c == -std::numeric_limits<double>::infinity())
        throw Error("solve_assignment: cost(" + std::to_string(i) + ", " + std::to_string(j) +
                    ") is NaN or -infinity (allowed: finite, or +infinity for a forbidden pair)");
      if (std::isfinite(c)) lo = std::min(lo, c), hi = std::max(hi, c);
    }
  }
  if (!std::isfinite(lo)) return std::vector<int>(n, -1);  // every pair forbidden
  // A forbidden pair costs more than any difference between two assignments' allowed pairs can
  // make up (at most min(n, m) pairs, each within [lo, hi]): fewer forbidden pairs always win.
  const double forbidden = hi + (hi - lo + 1.0) * (std::min(n, m) + 1);
  Eigen::MatrixXd a = cost.unaryExpr([&](double c) { return std::isfinite(c) ? c - lo : forbidden - lo; });
  const bool transposed = n > m;
  if (transposed) a.transposeInPlace();
  const std::vector<int> matched = assign_rows(a);
  std::vector<int> col_of(n, -1);
  for (std::size_t r = 0; r < matched.size(); ++r) {
    const int c = matched[r];
    if (c < 0) continue;
    const int i = transposed ? c : static_cast<int>(r), j = transposed ? static_cast<int>(r) : c;
    if (std::isfinite(cost(i, j))) col_of[i] = j;
  }
  return col_of;
}

}  // namespace bipednav::tracking
