#include "bipednav/tracking/hungarian.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <numeric>

#include "bipednav/common/error.hpp"
#include "bipednav/common/rng.hpp"

namespace bipednav::tracking {

namespace {

constexpr double kForbidden = std::numeric_limits<double>::infinity();

double total_cost(const Eigen::MatrixXd& c, const std::vector<int>& a) {
  double s = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i] >= 0) s += c(static_cast<Eigen::Index>(i), a[i]);
  return s;
}

// Every assignment of rows to distinct columns (or none), by enumeration: the most allowed pairs,
// then the least cost. Returns {pairs, cost}.
std::pair<int, double> brute_force(const Eigen::MatrixXd& c) {
  const auto n = static_cast<int>(c.rows()), m = static_cast<int>(c.cols());
  std::pair<int, double> best{-1, 0.0};
  std::vector<int> a(static_cast<std::size_t>(n), -1);
  std::vector<char> taken(static_cast<std::size_t>(m), 0);
  auto rec = [&](auto&& self, int i, int pairs, double cost) -> void {
    if (i == n) {
      if (pairs > best.first || (pairs == best.first && cost < best.second)) best = {pairs, cost};
      return;
    }
    self(self, i + 1, pairs, cost);
    for (int j = 0; j < m; ++j) {
      if (taken[static_cast<std::size_t>(j)] || c(i, j) == kForbidden) continue;
      taken[static_cast<std::size_t>(j)] = 1;
      self(self, i + 1, pairs + 1, cost + c(i, j));
      taken[static_cast<std::size_t>(j)] = 0;
    }
  };
  rec(rec, 0, 0, 0.0);
  return best;
}

}  // namespace

TEST(Hungarian, KnownSquareProblems) {
  Eigen::MatrixXd c(3, 3);
  c << 4, 1, 3, 2, 0, 5, 3, 2, 2;
  EXPECT_EQ(solve_assignment(c), (std::vector<int>{1, 0, 2}));  // 1 + 2 + 2 = 5
  // 69 + 37 + 11 + 23 = 140 (the least of the 24 assignments).
  Eigen::MatrixXd d(4, 4);
  d << 82, 83, 69, 92, 77, 37, 49, 92, 11, 69, 5, 86, 8, 9, 98, 23;
  const auto a = solve_assignment(d);
  EXPECT_EQ(a, (std::vector<int>{2, 1, 0, 3}));
  EXPECT_DOUBLE_EQ(total_cost(d, a), 140.0);
  // Negative costs are fine.
  Eigen::MatrixXd e(2, 2);
  e << -5, -1, -2, -9;
  EXPECT_EQ(solve_assignment(e), (std::vector<int>{0, 1}));
}

TEST(Hungarian, RectangularProblems) {
  Eigen::MatrixXd wide(2, 4);
  wide << 9, 2, 7, 1, 6, 4, 3, 8;
  EXPECT_EQ(solve_assignment(wide), (std::vector<int>{3, 2}));  // 1 + 3
  Eigen::MatrixXd tall = wide.transpose();
  EXPECT_EQ(solve_assignment(tall), (std::vector<int>{-1, -1, 1, 0}));
  EXPECT_EQ(solve_assignment(Eigen::MatrixXd(0, 3)), std::vector<int>{});
  EXPECT_EQ(solve_assignment(Eigen::MatrixXd(2, 0)), (std::vector<int>{-1, -1}));
}

TEST(Hungarian, ForbiddenPairsAreNeverAssignedAndMorePairsWin) {
  Eigen::MatrixXd c(3, 3);
  c << 1, kForbidden, kForbidden, 2, 100, kForbidden, kForbidden, kForbidden, kForbidden;
  // Row 0 to column 0 is cheapest alone, but row 1 can only take column 0 or 1: both pairs fit
  // with row 0 -> 0 and row 1 -> 1 (cost 101): the most pairs win over the least cost.
  EXPECT_EQ(solve_assignment(c), (std::vector<int>{0, 1, -1}));
  Eigen::MatrixXd all = Eigen::MatrixXd::Constant(2, 3, kForbidden);
  EXPECT_EQ(solve_assignment(all), (std::vector<int>{-1, -1}));
  Eigen::MatrixXd one(2, 2);
  one << kForbidden, 5, kForbidden, 3;
  const auto a = solve_assignment(one);
  EXPECT_EQ(a, (std::vector<int>{-1, 1}));
}

TEST(Hungarian, MatchesEnumerationOnRandomProblems) {
  Rng rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    const auto n = static_cast<int>(rng.uniform_int(1, 5)), m = static_cast<int>(rng.uniform_int(1, 5));
    Eigen::MatrixXd c(n, m);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < m; ++j) c(i, j) = rng.bernoulli(0.3) ? kForbidden : std::round(rng.uniform(-20, 50));
    const auto a = solve_assignment(c);
    const auto [pairs, cost] = brute_force(c);
    std::vector<int> cols;
    for (const int j : a) {
      if (j < 0) continue;
      cols.push_back(j);
    }
    std::sort(cols.begin(), cols.end());
    EXPECT_TRUE(std::adjacent_find(cols.begin(), cols.end()) == cols.end()) << "trial " << trial;
    EXPECT_EQ(static_cast<int>(cols.size()), pairs) << "trial " << trial;
    EXPECT_DOUBLE_EQ(total_cost(c, a), cost) << "trial " << trial;
  }
}

TEST(Hungarian, RejectsNaNAndMinusInfinity) {
  Eigen::MatrixXd c = Eigen::MatrixXd::Ones(2, 2);
  c(1, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(solve_assignment(c), Error);
  c(1, 0) = -kForbidden;
  EXPECT_THROW(solve_assignment(c), Error);
}

}  // namespace bipednav::tracking
