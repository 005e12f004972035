#include "bipednav/mapping/ray_trace.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <set>
#include <vector>

using namespace bipednav::mapping;

TEST(RayTrace, BresenhamLinesAreConnectedAndEndExact) {
  for (int bx = -7; bx <= 7; ++bx)
    for (int by = -7; by <= 7; ++by) {
      const auto cells = line_cells({2, 3}, {2 + bx, 3 + by});
      ASSERT_EQ(cells.size(), static_cast<std::size_t>(std::max(std::abs(bx), std::abs(by)) + 1));
      EXPECT_EQ(cells.front(), (Cell{2, 3}));
      EXPECT_EQ(cells.back(), (Cell{2 + bx, 3 + by}));
      for (std::size_t i = 1; i < cells.size(); ++i) {
        EXPECT_LE(std::abs(cells[i].x - cells[i - 1].x), 1);
        EXPECT_LE(std::abs(cells[i].y - cells[i - 1].y), 1);
      }
      // Every cell is within half a cell of the ideal line (Bresenham's error bound).
      for (const auto& c : cells) {
        const double cross = std::abs(double(bx) * (c.y - 3) - double(by) * (c.x - 2));
        EXPECT_LE(cross / std::max(1.0, std::hypot(bx, by)), 0.5 * std::sqrt(2.0) + 1e-9);
      }
      const auto open = line_cells({2, 3}, {2 + bx, 3 + by}, false);
      EXPECT_EQ(open.size(), cells.size() - 1);
    }
  const auto l = line_cells({0, 0}, {5, 2});
  const std::vector<Cell> expect{{0, 0}, {1, 0}, {2, 1}, {3, 1}, {4, 2}, {5, 2}};
  EXPECT_EQ(l, expect);
}

namespace {

// The textbook Bresenham line (a branch for the minor-axis step), the reference for the
// branch-free one in ray_trace.hpp.
std::vector<Cell> reference_line(Cell a, Cell b, bool include_end) {
  std::vector<Cell> out;
  const int dx = std::abs(b.x - a.x), dy = std::abs(b.y - a.y);
  const int sx = b.x >= a.x ? 1 : -1, sy = b.y >= a.y ? 1 : -1;
  const bool x_major = dx >= dy;
  const int n = x_major ? dx : dy, m = x_major ? dy : dx;
  int x = a.x, y = a.y, err = 2 * m - n;
  for (int k = 0; k < n; ++k) {
    out.push_back({x, y});
    if (err > 0) {
      (x_major ? y : x) += x_major ? sy : sx;
      err -= 2 * n;
    }
    err += 2 * m;
    (x_major ? x : y) += x_major ? sx : sy;
  }
  if (include_end) out.push_back({x, y});
  return out;
}

}  // namespace

TEST(RayTrace, LineIndicesAreTheLineCells) {
  // for_each_line_index visits exactly the reference line's cells, in order, with their indices;
  // line_cells (for_each_line_cell) gives the same cells.
  const int width = 37;
  for (const bool include_end : {true, false})
    for (int bx = -40; bx <= 40; ++bx)
      for (int by = -40; by <= 40; ++by) {
        const Cell a{50, 60}, b{50 + bx, 60 + by};
        const auto cells = reference_line(a, b, include_end);
        ASSERT_EQ(line_cells(a, b, include_end), cells) << bx << " " << by;
        std::vector<Cell> seen;
        for_each_line_index(a, b, include_end, width, [&](std::size_t i, int x, int y) {
          EXPECT_EQ(i, static_cast<std::size_t>(y) * width + static_cast<std::size_t>(x));
          seen.push_back({x, y});
        });
        ASSERT_EQ(seen, cells) << bx << " " << by;
      }
}

TEST(RayTrace, ClipSegmentToBox) {
  Eigen::Vector2d a(-1, 0.5), b(3, 0.5);
  ASSERT_TRUE(clip_segment(a, b, {0, 0}, {2, 1}));
  EXPECT_NEAR(a.x(), 0.0, 1e-12);
  EXPECT_NEAR(b.x(), 2.0, 1e-12);
  Eigen::Vector2d c(-1, 5), d(3, 5);
  EXPECT_FALSE(clip_segment(c, d, {0, 0}, {2, 1}));
}

TEST(RayTrace, ClipRayToRangeAndGrid) {
  const GridGeometry g{100, 100, 0.1, 0.0, 0.0};
  auto r = clip_ray(g, {1.05, 1.05}, {3.05, 1.05}, 10.0);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->start, (Cell{10, 10}));
  EXPECT_EQ(r->end, (Cell{30, 10}));
  EXPECT_FALSE(r->end_included);
  r = clip_ray(g, {1.05, 1.05}, {3.05, 1.05}, 1.0);  // clipped by range at x = 2.05
  ASSERT_TRUE(r);
  EXPECT_EQ(r->end, (Cell{20, 10}));
  EXPECT_TRUE(r->end_included);
  r = clip_ray(g, {1.05, 1.05}, {50.0, 1.05}, 100.0);  // leaves the grid
  ASSERT_TRUE(r);
  EXPECT_EQ(r->end, (Cell{99, 10}));
  EXPECT_TRUE(r->end_included);
  EXPECT_FALSE(clip_ray(g, {-1.0, 1.0}, {3.0, 1.0}, 10.0));  // origin outside
  EXPECT_FALSE(clip_ray(g, {1.0, 1.0}, {std::nan(""), 1.0}, 10.0));
}

// A return on the grid within range is not clipped: its ray ends in the return's own cell (which a
// clearing pass must not clear), whatever the rounding of origin + (return - origin).
TEST(RayTrace, ReturnsInsideTheGridAreNeverClipped) {
  const GridGeometry g{200, 150, 0.05, -3.7, -2.1};
  int rounding_cases = 0;
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector2d o(-3.7 + 0.0037 * (i % 997) + 1e-3, -2.1 + 0.0031 * (i % 907) + 1e-3);
    const Eigen::Vector2d p(-3.7 + 0.00493 * ((i * 7) % 1999) + 1e-3, -2.1 + 0.0037 * ((i * 13) % 1987) + 1e-3);
    rounding_cases += (o + (p - o)) != p ? 1 : 0;
    const auto r = clip_ray(g, o, p, 100.0);
    ASSERT_TRUE(r);
    EXPECT_FALSE(r->end_included) << i;
    EXPECT_EQ(r->end, *g.world_to_cell(p.x(), p.y())) << i;
  }
  EXPECT_GT(rounding_cases, 0);  // the inputs do exercise the rounding
}
