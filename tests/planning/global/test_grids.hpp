#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "bipednav/planning/global/global_planner.hpp"

namespace bipednav::planning::global::test {

inline mapping::Costmap2D make_map(int w, int h, double res = 1.0, std::uint8_t fill = mapping::kFree) {
  mapping::GridGeometry g;
  g.width = w;
  g.height = h;
  g.resolution_m = res;
  return mapping::Costmap2D(g, fill);
}

inline Pose2 centre(const mapping::Costmap2D& m, int x, int y, double yaw = 0.0) {
  const auto c = m.geometry().cell_center(x, y);
  return {c.x(), c.y(), yaw};
}

// Checks a successful plan against the cost model: starts at the start cell, ends at the goal cell
// (or, for an inscribed goal, the cell goal_search_cell picks within goal_tolerance_m), every step is one 8-neighbour
// move over traversable cells (the start may be exempt) without cutting a corner, and the step costs add up to the
// reported cost.
inline void expect_valid_path(const mapping::Costmap2D& map, const PlanResult& r, const GlobalPlannerParams& p,
                              const mapping::Cell& start, const mapping::Cell& goal) {
  ASSERT_TRUE(r.result.ok()) << r.result.message;
  ASSERT_FALSE(r.cells.empty());
  EXPECT_EQ(r.cells.front(), start);
  const auto end = goal_search_cell(map, centre(map, goal.x, goal.y), p);
  ASSERT_TRUE(end.has_value());
  EXPECT_EQ(r.cells.back(), *end);
  GridCostModel model(p.cost);
  model.assign(map);
  const std::size_t s = map.geometry().index(start);
  if (!model.passable(s)) model.set_exempt(static_cast<std::int64_t>(s));
  Cost cost = 0;
  for (std::size_t i = 1; i < r.cells.size(); ++i) {
    const auto& a = r.cells[i - 1];
    const auto& b = r.cells[i];
    int k = 0;
    while (k < kNumNeighbours && (a.x + kDx[k] != b.x || a.y + kDy[k] != b.y)) ++k;
    ASSERT_LT(k, kNumNeighbours) << "cells " << i - 1 << " and " << i << " are not neighbours";
    const Cost c = model.edge_cost(a.x, a.y, k);  // kInfCost for blocked cells or a cut corner
    ASSERT_LT(c, kInfCost) << "step " << i << " enters a blocked cell or cuts a corner";
    cost += c;
  }
  EXPECT_DOUBLE_EQ(model.to_metres(cost), r.cost);
  ASSERT_GE(r.path.poses.size(), 2u);
}

}  // namespace bipednav::planning::global::test
