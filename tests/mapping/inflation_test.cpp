#include "bipednav/mapping/inflation.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "bipednav/common/error.hpp"
#include "bipednav/common/rng.hpp"

using namespace bipednav::mapping;

namespace {

InflationParams params(double inscribed, double inflation, double k) { return {inscribed, inflation, k}; }

// Brute force: the cost of every cell from its distance to the nearest lethal cell.
Costmap2D brute_inflate(const Costmap2D& obstacles, const InflationParams& p) {
  Costmap2D out(obstacles.geometry(), kFree);
  const double res = obstacles.resolution_m();
  for (int y = 0; y < obstacles.height(); ++y)
    for (int x = 0; x < obstacles.width(); ++x) {
      double best = 1e18;
      for (int v = 0; v < obstacles.height(); ++v)
        for (int u = 0; u < obstacles.width(); ++u)
          if (obstacles.cost(u, v) == kLethal) best = std::min(best, std::hypot(u - x, v - y) * res);
      out.set_cost(x, y, best > 1e17 ? kFree : inflation_cost(best, p));
    }
  return out;
}

}  // namespace

TEST(Inflation, CostFormulaAtKnownDistances) {
  const auto p = params(0.2, 0.6, 3.0);
  EXPECT_EQ(inflation_cost(0.0, p), kLethal);
  EXPECT_EQ(inflation_cost(0.05, p), kInscribed);
  EXPECT_EQ(inflation_cost(0.2, p), kInscribed);
  // 252 * exp(-3 * 0.05) = 216.9 -> 216 ; 252 * exp(-3 * 0.4) = 75.9 -> 75
  EXPECT_EQ(inflation_cost(0.25, p), 216);
  EXPECT_EQ(inflation_cost(0.6, p), 75);
  EXPECT_EQ(inflation_cost(0.6001, p), kFree);
  EXPECT_EQ(inflation_cost(5.0, p), kFree);
}

TEST(Inflation, SingleObstacleExactCosts) {
  Costmap2D obstacles({41, 41, 0.05, 0.0, 0.0}, kFree);
  obstacles.set_cost(20, 20, kLethal);
  const auto p = params(0.2, 0.6, 3.0);
  Inflator inflator(p, 0.05);
  EXPECT_EQ(inflator.radius_cells(), 12);
  Costmap2D out;
  inflator.inflate(obstacles, out);
  EXPECT_EQ(out.cost(20, 20), kLethal);
  EXPECT_EQ(out.cost(24, 20), kInscribed);  // 0.20 m
  EXPECT_EQ(out.cost(20, 25), 216);         // 0.25 m
  EXPECT_EQ(out.cost(32, 20), 75);          // 0.60 m
  EXPECT_EQ(out.cost(33, 20), kFree);       // 0.65 m
  EXPECT_EQ(out.cost(23, 24), 216);         // 3-4-5: 0.25 m diagonal
  for (int y = 0; y < 41; ++y)
    for (int x = 0; x < 41; ++x)
      ASSERT_EQ(out.cost(x, y), inflation_cost(std::hypot(x - 20, y - 20) * 0.05, p)) << x << "," << y;
}

TEST(Inflation, MatchesBruteForceOnRandomMaps) {
  bipednav::Rng rng(7);
  for (int trial = 0; trial < 6; ++trial) {
    const int w = 20 + static_cast<int>(rng.uniform_int(0, 30)), h = 20 + static_cast<int>(rng.uniform_int(0, 30));
    const double res = trial % 2 ? 0.05 : 0.1;
    Costmap2D obstacles({w, h, res, -1.0, 2.0}, kFree);
    for (auto& v : obstacles.data()) v = rng.bernoulli(0.03) ? kLethal : (rng.bernoulli(0.05) ? kUnknown : kFree);
    const auto p = params(0.1 + 0.05 * trial, 0.4 + 0.1 * trial, 1.0 + trial);
    Inflator inflator(p, res);
    Costmap2D out;
    inflator.inflate(obstacles, out);
    const Costmap2D expect = brute_inflate(obstacles, p);
    EXPECT_TRUE(diff(expect, out).empty()) << "trial " << trial;
    // A region update writes exactly the region, with the same values.
    Costmap2D partial(obstacles.geometry(), 77);
    const CellRect region{3, 5, w - 4, h - 2};
    inflator.inflate(obstacles, partial, region);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) ASSERT_EQ(partial.cost(x, y), region.contains(x, y) ? expect.cost(x, y) : 77);
  }
}

TEST(Inflation, RejectsBadParams) {
  EXPECT_THROW(Inflator(params(0.5, 0.2, 3.0), 0.05), bipednav::ParamError);
  EXPECT_THROW(Inflator(params(-0.1, 0.2, 3.0), 0.05), bipednav::ParamError);
  EXPECT_THROW(Inflator(params(0.1, 0.2, std::nan("")), 0.05), bipednav::ParamError);
  EXPECT_THROW(Inflator(params(0.1, 0.2, 3.0), 0.0), bipednav::ParamError);
}
