#include "bipednav/tracking/static_structure.hpp"

#include <gtest/gtest.h>

#include "tracking/tracking_test_utils.hpp"

namespace bipednav::tracking {

TEST(StaticStructure, IsLethalCellsOfAGivenAge) {
  mapping::Costmap2D m = test::free_grid(0.0, 0.0, 4.0, 0.1);
  const auto cell = *m.geometry().world_to_cell(1.0, 1.0);
  const Eigen::Vector2d at(1.05, 1.05), beside(1.25, 1.05);
  StaticStructure s;
  EXPECT_TRUE(s.empty());
  EXPECT_FALSE(s.near(at, 0.2, 0.0));
  m.set_cost(cell, mapping::kLethal);
  s.update(m, 0.0);
  EXPECT_TRUE(s.near(at, 0.0, 0.0));
  EXPECT_FALSE(s.near(at, 0.0, 4.0));  // not old enough yet
  s.update(m, 3.9);
  EXPECT_FALSE(s.near(at, 0.0, 4.0));
  s.update(m, 4.0);
  EXPECT_TRUE(s.near(at, 0.0, 4.0));
  EXPECT_TRUE(s.near(beside, 0.2, 4.0));  // within the margin
  EXPECT_FALSE(s.near(beside, 0.1, 4.0));
  s.update(m, 3.0);  // a time that does not advance changes nothing
  EXPECT_TRUE(s.near(at, 0.0, 4.0));
  m.set_cost(cell, mapping::kFree);  // cleared: its age starts over when it is marked again
  s.update(m, 5.0);
  EXPECT_FALSE(s.near(at, 0.0, 0.0));
  m.set_cost(cell, mapping::kLethal);
  s.update(m, 6.0);
  s.update(m, 9.9);
  EXPECT_FALSE(s.near(at, 0.0, 4.0));
  s.update(m, 10.0);
  EXPECT_TRUE(s.near(at, 0.0, 4.0));
}

}  // namespace bipednav::tracking
