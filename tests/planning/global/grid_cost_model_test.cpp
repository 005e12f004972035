#include "bipednav/planning/global/grid_cost_model.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "bipednav/common/error.hpp"
#include "bipednav/common/rng.hpp"
#include "bipednav/planning/global/indexed_heap.hpp"
#include "test_grids.hpp"

using namespace bipednav;
using namespace bipednav::planning::global;

namespace {

TEST(CellFactor, FollowsTheCostFormula) {
  GridCostParams p;
  p.cost_weight = 3.0;
  EXPECT_DOUBLE_EQ(cell_factor(0, p), 1.0);
  EXPECT_DOUBLE_EQ(cell_factor(84, p), 2.0);
  EXPECT_DOUBLE_EQ(cell_factor(252, p), 4.0);
  EXPECT_TRUE(std::isinf(cell_factor(mapping::kInscribed, p)));
  EXPECT_TRUE(std::isinf(cell_factor(mapping::kLethal, p)));
  EXPECT_DOUBLE_EQ(cell_factor(mapping::kUnknown, p), 1.0);
  p.unknown_cost = 84;
  EXPECT_DOUBLE_EQ(cell_factor(mapping::kUnknown, p), 2.0);
  p.unknown_is_obstacle = true;
  EXPECT_TRUE(std::isinf(cell_factor(mapping::kUnknown, p)));
}

TEST(CellFactor, ClosesMappedCellsFromMinImpassableCost) {
  GridCostParams p;
  p.min_impassable_cost = 193;
  EXPECT_DOUBLE_EQ(cell_factor(84, p), 2.0);
  EXPECT_TRUE(std::isfinite(cell_factor(192, p)));
  EXPECT_TRUE(std::isinf(cell_factor(193, p)));
  EXPECT_TRUE(std::isinf(cell_factor(252, p)));
  EXPECT_DOUBLE_EQ(cell_factor(mapping::kUnknown, p), 1.0);  // unknown cells keep their own rule
  p.min_impassable_cost = 0;
  EXPECT_THROW(p.validate(), ParamError);
  p.min_impassable_cost = 254;
  EXPECT_THROW(p.validate(), ParamError);
}

TEST(MinImpassableCost, ClosesTheCellsNearerThanTheClearance) {
  const mapping::InflationParams inflation{0.38, 0.83, 3.0};
  // Within the inscribed radius: the inscribed cells, as without a clearance.
  EXPECT_EQ(min_impassable_cost(0.38, inflation), mapping::kInscribed);
  EXPECT_EQ(min_impassable_cost(0.2, inflation), mapping::kInscribed);
  // 0.47 m: 252 exp(-3 x 0.09) = 192.4 -> cells costing 193 or more (nearer than 0.47 m) close.
  const int c = min_impassable_cost(0.47, inflation);
  EXPECT_EQ(c, 193);
  EXPECT_GE(mapping::inflation_cost(0.4, inflation), c);   // 237
  EXPECT_GE(mapping::inflation_cost(0.46, inflation), c);  // 197
  EXPECT_LT(mapping::inflation_cost(0.47, inflation), c);
  EXPECT_LT(mapping::inflation_cost(0.5, inflation), c);  // 175
  // Beyond the inflation radius (costs 0 there) every inflated cell closes: 252 exp(-1.35) = 65.3.
  EXPECT_EQ(min_impassable_cost(1.0, inflation), 66);
}

TEST(GridCostModel, EdgeCostsAreSymmetricAndForbidCornerCutting) {
  auto map = test::make_map(3, 3, 0.5);
  map.set_cost(1, 1, 84);
  map.set_cost(2, 1, mapping::kLethal);
  GridCostModel m;
  m.assign(map);
  // (0,0) -> (1,0): mean factor 1, 0.5 m.
  EXPECT_DOUBLE_EQ(m.to_metres(m.edge_cost(0, 0, 0)), 0.5);
  // (0,1) -> (1,1): mean of 1 and 2.
  EXPECT_DOUBLE_EQ(m.to_metres(m.edge_cost(0, 1, 0)), 0.75);
  EXPECT_EQ(m.edge_cost(0, 1, 0), m.edge_cost(1, 1, 2));
  // Into the lethal cell, off the grid, into it diagonally, and diagonals passing its corner.
  EXPECT_EQ(m.edge_cost(1, 1, 0), kInfCost);
  EXPECT_EQ(m.edge_cost(2, 2, 0), kInfCost);
  EXPECT_EQ(m.edge_cost(1, 0, 4), kInfCost);  // (1,0) -> (2,1) is lethal
  EXPECT_EQ(m.edge_cost(1, 2, 7), kInfCost);  // (1,2) -> (2,1)
  EXPECT_EQ(m.edge_cost(1, 0, 4), m.edge_cost(2, 1, 6));
  EXPECT_EQ(m.edge_cost(2, 0, 5), kInfCost);  // (2,0) -> (1,1) passes beside lethal (2,1)
  EXPECT_NEAR(m.to_metres(m.edge_cost(0, 0, 4)), 0.5 * std::sqrt(2.0) * 1.5, 1e-7);
}

TEST(GridCostModel, HeuristicIsConsistentOnRandomCosts) {
  Rng rng(3);
  auto map = test::make_map(20, 20, 0.1);
  for (auto& c : map.data()) c = static_cast<std::uint8_t>(rng.uniform_int(0, 255));
  GridCostModel m;
  m.assign(map);
  const std::size_t goal = m.idx(17, 3);
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 20; ++x)
      for (int k = 0; k < kNumNeighbours; ++k) {
        const Cost c = m.edge_cost(x, y, k);
        if (c >= kInfCost) continue;
        EXPECT_LE(m.heuristic(m.idx(x, y), goal), c + m.heuristic(m.idx(x + kDx[k], y + kDy[k]), goal));
      }
}

TEST(GridCostModel, ExemptCellBecomesTraversable) {
  auto map = test::make_map(2, 1, 1.0, mapping::kInscribed);
  map.set_cost(1, 0, 0);
  GridCostModel m;
  m.assign(map);
  EXPECT_EQ(m.edge_cost(0, 0, 0), kInfCost);
  m.set_exempt(0);
  EXPECT_DOUBLE_EQ(m.to_metres(m.edge_cost(0, 0, 0)), (4.0 + 1.0) / 2.0);
}

TEST(IndexedHeap, OrdersUpdatesAndRemoves) {
  IndexedHeap h;
  h.resize(100);
  Rng rng(9);
  std::vector<Key> key(100);
  std::vector<bool> in(100, false);
  for (int it = 0; it < 5000; ++it) {
    const auto v = static_cast<std::size_t>(rng.uniform_int(0, 99));
    const int op = static_cast<int>(rng.uniform_int(0, 2));
    if (op < 2) {
      key[v] = {rng.uniform_int(0, 20), rng.uniform_int(0, 20)};
      h.push(v, key[v]);
      in[v] = true;
    } else if (in[v]) {
      h.remove(v);
      in[v] = false;
    }
    ASSERT_EQ(h.size(), static_cast<std::size_t>(std::count(in.begin(), in.end(), true)));
    if (h.empty()) continue;
    Key best{kInfCost, kInfCost};
    for (std::size_t u = 0; u < 100; ++u)
      if (in[u] && key[u] < best) best = key[u];
    ASSERT_EQ(h.top_key(), best);
  }
  while (!h.empty()) {
    const Key k = h.top_key();
    h.pop();
    if (!h.empty()) {
      ASSERT_FALSE(h.top_key() < k);
    }
  }
}

}  // namespace
