#include "bipednav/viz/figure_legend.hpp"

#include <gtest/gtest.h>

using namespace bipednav::viz;

TEST(FigureLegend, ScaleBarLengthIsRound) {
  EXPECT_DOUBLE_EQ(scale_bar_length_m(1.0), 1.0);
  EXPECT_DOUBLE_EQ(scale_bar_length_m(1.9), 1.0);
  EXPECT_DOUBLE_EQ(scale_bar_length_m(2.0), 2.0);
  EXPECT_DOUBLE_EQ(scale_bar_length_m(4.99), 2.0);
  EXPECT_DOUBLE_EQ(scale_bar_length_m(7.3), 5.0);
  EXPECT_NEAR(scale_bar_length_m(0.3), 0.2, 1e-12);
  EXPECT_DOUBLE_EQ(scale_bar_length_m(0.0), 0.0);
}

TEST(FigureLegend, BandsMakeRoomForTheLegend) {
  CanvasParams p;
  p.min_x_m = 0, p.max_x_m = 2, p.min_y_m = 0, p.max_y_m = 1, p.pixels_per_m = 50, p.margin_px = 10;
  const std::vector<LegendEntry> entries = {{"a path", colors::kRed},
                                            {"an area", colors::kBlue, LegendMark::kBox},
                                            {"a pose", colors::kBlack, LegendMark::kArrow}};
  const CanvasParams b = with_legend_bands(p, entries);
  EXPECT_GT(b.top_px, 0);
  Canvas c(b);
  const PixelRect legend = legend_extent(c, entries);
  EXPECT_GE(b.right_px, legend.w);
  // The 50 px tall window is shorter than the legend and the scale bar: room is made below it.
  EXPECT_GE(c.height_px(), b.margin_px + b.top_px + legend.h + 50.0);
  const PixelRect world = c.world_rect();
  EXPECT_DOUBLE_EQ(world.y, 10.0 + b.top_px);
  EXPECT_TRUE(c.to_pixel({0, 1}).isApprox(Eigen::Vector2d(world.x, world.y)));
  const PixelRect rest = draw_title_and_legend(c, "title", entries);
  EXPECT_GE(rest.x, world.right());
  EXPECT_LE(rest.right(), c.width_px());
}
