#include "bipednav/mapping/ray_trace.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <optional>
#include <set>
#include <vector>

using namespace bipednav::mapping;

namespace {

// The cells of the Bresenham line from `a` to `b`, as for_each_line_cell visits them.
std::vector<Cell> line_cells(Cell a, Cell b, bool include_end = true) {
  std::vector<Cell> out;
  for_each_line_cell(a, b, include_end, [&](int x, int y) { out.push_back({x, y}); });
  return out;
}

}  // namespace

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

namespace {

// Returns around a grid: most on it and in range, some on cell edges (and a float step either
// side), beyond the ranges, off the grid, at the box's edge, or not finite.
std::vector<Eigen::Vector3f> cell_test_points(const GridGeometry& g) {
  std::vector<Eigen::Vector3f> pts;
  std::uint32_t s = 12345;
  const auto uniform = [&](double lo, double hi) {
    s = s * 1664525u + 1013904223u;
    return lo + (hi - lo) * ((s >> 8) / double(1u << 24));
  };
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  for (int i = 0; i < 20000; ++i) {
    Eigen::Vector3f p(static_cast<float>(uniform(g.origin_x_m - 1.0, g.origin_x_m + g.size_x_m() + 1.0)),
                      static_cast<float>(uniform(g.origin_y_m - 1.0, g.origin_y_m + g.size_y_m() + 1.0)),
                      static_cast<float>(uniform(-1.0, 3.0)));
    switch (i % 11) {
      case 0:  // on a cell edge, or a float step off it
      case 1: {
        const float ex = static_cast<float>(g.origin_x_m + g.resolution_m * std::floor(uniform(0.0, g.width)));
        const float ey = static_cast<float>(g.origin_y_m + g.resolution_m * std::floor(uniform(0.0, g.height)));
        const int step = i % 3 - 1;
        p.x() = step == 0 ? ex : std::nextafter(ex, step * inf);
        p.y() = i % 2 ? ey : std::nextafter(ey, -inf);
        break;
      }
      case 2:
        p[i % 3] = (i / 11) % 3 == 0 ? nan : ((i / 11) % 3 == 1 ? inf : -inf);
        break;
      case 3:  // the grid's far edges
        p.x() = static_cast<float>(g.origin_x_m + g.size_x_m());
        p.y() = std::nextafter(static_cast<float>(g.origin_y_m + g.size_y_m()), -inf);
        break;
      default:
        break;
    }
    pts.push_back(p);
  }
  return pts;
}

}  // namespace

// RayClipper::end_cells and point_cells (four points at a time where the CPU has AVX2) give what
// the one-point code gives, for every count of points (the tails after the groups of four).
TEST(RayTrace, EndCellsArePerPointCells) {
  const GridGeometry g{160, 140, 0.05, -4.05, -3.5};
  const auto pts = cell_test_points(g);
  int cells = 0, clipped = 0, skipped = 0;
  for (const Eigen::Vector3d& origin : {Eigen::Vector3d(0.013, -0.27, 0.4), Eigen::Vector3d(-4.049, 3.49, 1.47),
                                        Eigen::Vector3d(-9.0, 0.0, 0.3)}) {  // the last outside the grid
    for (const double max_len : {5.0, 1.3}) {
      const RayClipper clipper(g, origin.head<2>(), max_len);
      for (const double range : {2.9, 100.0}) {
        const double range_sq = range * range;
        for (const std::size_t n : {pts.size(), std::size_t{7}, std::size_t{2}}) {
          std::vector<std::int32_t> end(n, 7), cell(n, 7);
          clipper.end_cells(pts.data(), n, origin, range_sq, end.data());
          point_cells(g, pts.data(), n, origin, range_sq, cell.data());
          for (std::size_t k = 0; k < n; ++k) {
            const Eigen::Vector3f& p = pts[k];
            const bool kept = p.allFinite() && (p.cast<double>() - origin).squaredNorm() <= range_sq;
            const auto own = kept ? g.world_to_cell(p.x(), p.y()) : std::nullopt;
            ASSERT_EQ(cell[k], own ? static_cast<std::int32_t>(g.index(*own)) : kNoCell) << k;
            const auto e = kept ? clipper.unclipped_end(p.head<2>().cast<double>()) : std::nullopt;
            ASSERT_EQ(end[k], !kept ? kNoCell : (e ? static_cast<std::int32_t>(g.index(*e)) : kClipCell)) << k;
            cells += end[k] >= 0;
            clipped += end[k] == kClipCell;
            skipped += end[k] == kNoCell;
          }
        }
      }
    }
  }
  EXPECT_GT(cells, 10000);  // every outcome is exercised
  EXPECT_GT(clipped, 10000);
  EXPECT_GT(skipped, 10000);
}
