// The global map's grid from a map area (a robot node's parameters, a scenario's bounds).
#include "bipednav/navigation/map_area.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "bipednav/common/error.hpp"

using namespace bipednav;
using navigation::global_grid_for;
using navigation::MapArea;

TEST(MapArea, TheGridCoversTheAreaWithItsOriginOnAMultipleOfTheResolution) {
  // The real robot launch file's default area, at 0.1 m: 100 x 80 cells from (-5, -4).
  const mapping::GridGeometry g = global_grid_for({-5.0, -4.0, 5.0, 4.0}, 0.1);
  EXPECT_EQ(g.width, 100);
  EXPECT_EQ(g.height, 80);
  EXPECT_DOUBLE_EQ(g.origin_x_m, -5.0);
  EXPECT_DOUBLE_EQ(g.origin_y_m, -4.0);
  EXPECT_EQ(g.resolution_m, 0.1);
  // Corners off the grid's multiples: the origin rounds down, the far side up.
  const mapping::GridGeometry h = global_grid_for({-1.23, 0.42, 2.01, 1.0}, 0.5);
  EXPECT_DOUBLE_EQ(h.origin_x_m, -1.5);
  EXPECT_DOUBLE_EQ(h.origin_y_m, 0.0);
  EXPECT_EQ(h.width, 8);   // -1.5 .. 2.5
  EXPECT_EQ(h.height, 2);  // 0 .. 1
}

TEST(MapArea, TheMarginWidensEverySide) {
  MapArea a{0.0, 0.0, 4.0, 2.0};
  a.margin_m = 2.0;
  const mapping::GridGeometry g = global_grid_for(a, 0.25);
  EXPECT_DOUBLE_EQ(g.origin_x_m, -2.0);
  EXPECT_DOUBLE_EQ(g.origin_y_m, -2.0);
  EXPECT_EQ(g.width, 32);   // -2 .. 6
  EXPECT_EQ(g.height, 24);  // -2 .. 4
}

TEST(MapArea, NonsenseIsRejectedWithTheFieldNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(global_grid_for({1.0, 0.0, 1.0, 1.0}, 0.1), ParamError);  // min_x == max_x
  EXPECT_THROW(global_grid_for({0.0, 2.0, 1.0, 1.0}, 0.1), ParamError);  // min_y > max_y
  EXPECT_THROW(global_grid_for({nan, 0.0, 1.0, 1.0}, 0.1), ParamError);
  EXPECT_THROW(global_grid_for({0.0, 0.0, 1.0, 1.0, -0.5}, 0.1), ParamError);
  EXPECT_THROW(global_grid_for({0.0, 0.0, 1.0, 1.0}, 0.0), ParamError);
  try {
    global_grid_for({-1e9, 0.0, 1e9, 1.0}, 0.05);
    FAIL() << "no error";
  } catch (const ParamError& e) {
    EXPECT_NE(std::string(e.what()).find("at most a million cells a side"), std::string::npos) << e.what();
  }
}
