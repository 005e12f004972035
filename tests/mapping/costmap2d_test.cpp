#include "bipednav/mapping/costmap2d.hpp"

#include <gtest/gtest.h>

using namespace bipednav::mapping;

TEST(Costmap2D, WorldCellConversionsAndBounds) {
  Costmap2D map({100, 50, 0.1, -5.0, -2.5});
  auto c = map.geometry().world_to_cell(0.05, 0.05);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->x, 50);
  EXPECT_EQ(c->y, 25);
  EXPECT_FALSE(map.geometry().world_to_cell(5.01, 0.0));
  EXPECT_FALSE(map.geometry().world_to_cell(std::nan(""), 0.0));
  const auto w = map.geometry().cell_center(50, 25);
  EXPECT_NEAR(w.x(), 0.05, 1e-12);
  EXPECT_NEAR(w.y(), 0.05, 1e-12);
}

TEST(Costmap2D, ShiftOriginKeepsOverlappingCells) {
  Costmap2D map({10, 10, 1.0, 0.0, 0.0});
  map.set_cost(5, 5, kLethal);
  map.shift_origin(2.0, 1.0, kUnknown);
  EXPECT_EQ(map.cost(3, 4), kLethal);
  EXPECT_EQ(map.cost(9, 9), kUnknown);
  EXPECT_DOUBLE_EQ(map.geometry().origin_x_m, 2.0);
  Costmap2D other = map;
  other.set_cost(0, 0, 7);
  const ChangeSet d = diff(map, other);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].new_cost, 7);
}
