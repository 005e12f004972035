#include "bipednav/viz/figure_layout.hpp"

#include <gtest/gtest.h>

#include "bipednav/common/error.hpp"

using namespace bipednav;
using namespace bipednav::viz;

namespace {

// run.png's world windows (the scenario's bounds plus 0.5 m on each side): three_rooms is
// 30.2 x 6.2 m; a BARN world (tests/data/barn, a 4.6 x 10 m cylinder field) with the usual start
// (-2.25, 3) and goal 10 m ahead (-2.25, 13) spans about 4.6 x 13.6 m.
constexpr double kThreeRoomsW = 31.2, kThreeRoomsH = 7.2;
constexpr double kBarnW = 5.6, kBarnH = 14.6;

FigureLayoutParams with_legend() {
  FigureLayoutParams p;
  p.legend_w_px = 230.0;
  p.legend_h_px = 290.0;
  return p;
}

bool inside(const PixelRect& r, const FigureLayout& l) {
  return r.x >= 0 && r.y >= 0 && r.right() <= l.width_px + 1e-9 && r.bottom() <= l.height_px + 1e-9;
}

// Every panel, title, the header and the legend lie inside the picture, none overlaps another,
// and each panel holds the world window at the layout's scale.
void expect_sound(const FigureLayout& l, double w_m, double h_m, std::size_t panels) {
  ASSERT_EQ(l.panels.size(), panels);
  ASSERT_EQ(l.titles.size(), panels);
  std::vector<PixelRect> all = {l.header, l.legend};
  all.insert(all.end(), l.panels.begin(), l.panels.end());
  all.insert(all.end(), l.titles.begin(), l.titles.end());
  for (std::size_t i = 0; i < all.size(); ++i) {
    EXPECT_TRUE(inside(all[i], l)) << "rectangle " << i;
    for (std::size_t j = i + 1; j < all.size(); ++j) EXPECT_FALSE(overlap(all[i], all[j])) << i << " and " << j;
  }
  for (std::size_t i = 0; i < panels; ++i) {
    EXPECT_NEAR(l.panels[i].w, w_m * l.pixels_per_m, 1e-9);
    EXPECT_NEAR(l.panels[i].h, h_m * l.pixels_per_m, 1e-9);
    EXPECT_NEAR(l.titles[i].bottom(), l.panels[i].y, 1e-9) << "the title sits right above its panel";
  }
}

}  // namespace

// 1 to 4 panels (the end of the run and up to 3 replanning snapshots) of a world window: sound,
// within the size limits, in one row (tall worlds) or one column (wide worlds).
void expect_panels_in_line(double w_m, double h_m, bool one_row) {
  for (std::size_t n = 1; n <= 4; ++n) {
    const FigureLayout l = figure_layout(w_m, h_m, n, with_legend());
    expect_sound(l, w_m, h_m, n);
    EXPECT_EQ(one_row ? l.rows : l.columns, 1) << n << " panels";
    EXPECT_LE(l.width_px, 1800);
    EXPECT_LE(l.height_px, 1300);
  }
}

TEST(FigureLayout, TallBarnWorldPanelsSideBySide) { expect_panels_in_line(kBarnW, kBarnH, true); }

TEST(FigureLayout, WideThreeRoomsPanelsStacked) { expect_panels_in_line(kThreeRoomsW, kThreeRoomsH, false); }

TEST(FigureLayout, ScaleIsTheLargestThatFits) {
  FigureLayoutParams p;  // no legend; margins 12, header 28, titles 22, gaps 14
  p.max_pixels_per_m = 1000.0;
  // One 10 x 5 m panel: width allows (1800 - 24) / 10 = 177.6 px/m, height (1300 - 24 - 28 - 22) / 5 = 245.2.
  const FigureLayout one = figure_layout(10.0, 5.0, 1, p);
  EXPECT_NEAR(one.pixels_per_m, 177.6, 1e-9);
  EXPECT_EQ(one.width_px, 1800);
  // Two square 10 x 10 m panels: side by side (1800 - 24 - 14) / 20 = 88.1, stacked
  // (1300 - 24 - 28 - 44 - 14) / 20 = 59.5: side by side wins.
  const FigureLayout two = figure_layout(10.0, 10.0, 2, p);
  EXPECT_EQ(two.columns, 2);
  EXPECT_NEAR(two.pixels_per_m, 88.1, 1e-9);
  expect_sound(two, 10.0, 10.0, 2);
}

TEST(FigureLayout, ExtremeAspectRatiosAndLegendTallerThanPanels) {
  for (const auto& [w, h] : {std::pair{100.0, 1.0}, {1.0, 100.0}, {0.5, 0.5}}) {
    FigureLayoutParams p = with_legend();
    p.legend_h_px = 2000.0;
    const FigureLayout l = figure_layout(w, h, 3, p);
    expect_sound(l, w, h, 3);
    EXPECT_GE(l.height_px, 2000);
  }
}

TEST(FigureLayout, RejectsEmptyOrNonFiniteInput) {
  EXPECT_THROW(figure_layout(0.0, 5.0, 1), ParamError);
  EXPECT_THROW(figure_layout(5.0, std::nan(""), 1), ParamError);
  EXPECT_THROW(figure_layout(5.0, 5.0, 0), ParamError);
  FigureLayoutParams p;
  p.gap_px = -1.0;
  EXPECT_THROW(figure_layout(5.0, 5.0, 1, p), ParamError);
}

TEST(FigureLayout, OverlapIgnoresTouchingEdges) {
  EXPECT_FALSE(overlap({0, 0, 10, 10}, {10, 0, 10, 10}));
  EXPECT_TRUE(overlap({0, 0, 10, 10}, {9.5, 9.5, 10, 10}));
}
