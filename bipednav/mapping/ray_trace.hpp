#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <vector>

#include "bipednav/mapping/grid_geometry.hpp"

namespace bipednav::mapping {

// Visits the cells of the 8-connected Bresenham line from `a` to `b` on a row-major grid `width`
// cells wide, each with its index (y * width + x): `a` first, `b` last (only when `include_end`).
// Every step moves one cell along the major axis, so the line has max(|dx|, |dy|) + 1 cells and no
// cell twice. The minor-axis step is taken without a branch: on a ray trace's long lines it is
// taken at random and mispredicted often.
template <typename Visit>
void for_each_line_index(Cell a, Cell b, bool include_end, int width, Visit&& visit) {
  const int dx = std::abs(b.x - a.x), dy = std::abs(b.y - a.y);
  const int sx = b.x >= a.x ? 1 : -1, sy = b.y >= a.y ? 1 : -1;
  const bool x_major = dx >= dy;
  const int n = x_major ? dx : dy, m = x_major ? dy : dx;  // steps along the major and minor axis
  const int major_x = x_major ? sx : 0, major_y = x_major ? 0 : sy;
  const int minor_x = x_major ? 0 : sx, minor_y = x_major ? sy : 0;
  const std::ptrdiff_t w = width;
  const std::ptrdiff_t major_i = major_y * w + major_x, minor_i = minor_y * w + minor_x;
  int x = a.x, y = a.y;
  std::ptrdiff_t i = a.y * w + a.x;
  int err = 2 * m - n;
  for (int k = 0; k < n; ++k) {
    visit(static_cast<std::size_t>(i), x, y);
    const int step = -static_cast<int>(err > 0);  // all ones when the minor axis steps
    x += minor_x & step;
    y += minor_y & step;
    i += minor_i & step;
    err -= (2 * n) & step;
    err += 2 * m;
    x += major_x;
    y += major_y;
    i += major_i;
  }
  if (include_end) visit(static_cast<std::size_t>(i), x, y);
}

// for_each_line_index without the grid: visit(x, y) for the same cells in the same order.
template <typename Visit>
void for_each_line_cell(Cell a, Cell b, bool include_end, Visit&& visit) {
  for_each_line_index(a, b, include_end, 0, [&](std::size_t, int x, int y) { visit(x, y); });
}

// Clips the segment a-b to the axis-aligned box [lo, hi] (Liang-Barsky). Returns false when the
// segment misses the box; otherwise moves a and/or b onto the box boundary.
bool clip_segment(Eigen::Vector2d& a, Eigen::Vector2d& b, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi);

// A ray from a sensor to a return, clipped to the grid and to a maximum length, in cells.
// `end_included` is true when the ray was clipped (the return lies beyond `end`, so the end cell
// was seen free); false when `end` is the return's own cell (an obstacle, not to be cleared).
struct ClippedRay {
  Cell start;
  Cell end;
  bool end_included = false;
};

// Clips the ray origin->point to `max_length_m` and to the grid. nullopt when the origin is
// outside the grid or any coordinate is not finite.
std::optional<ClippedRay> clip_ray(const GridGeometry& g, const Eigen::Vector2d& origin, const Eigen::Vector2d& point,
                                   double max_length_m);

// Codes of RayClipper::end_cells and point_cells for a point without a cell of its own.
inline constexpr std::int32_t kNoCell = -1;    // not finite, out of range (or, point_cells: off the grid)
inline constexpr std::int32_t kClipCell = -2;  // end_cells: the ray needs RayClipper::clip

// For each of `n` points (map frame): the grid index of its cell when it is finite, no farther
// than sqrt(range_sq) from `origin` (3D distance, in double) and on the grid; kNoCell otherwise.
// The same as g.world_to_cell(p.x(), p.y()) after those checks, four points at a time where the
// CPU has AVX2.
void point_cells(const GridGeometry& g, const Eigen::Vector3f* points, std::size_t n, const Eigen::Vector3d& origin,
                 double range_sq, std::int32_t* out);

// clip_ray for many rays from one origin: the origin's cell and the grid box are computed once,
// and a return on the grid within range (most of them) takes its cell directly, without clipping
// or a square root.
class RayClipper {
 public:
  RayClipper(const GridGeometry& g, const Eigen::Vector2d& origin, double max_length_m);
  std::optional<ClippedRay> clip(const Eigen::Vector2d& point) const;
  // The common case inline: a return on the grid within range (the origin on the grid too) gives
  // its own cell, and clip(point) is {start, that cell, false}. nullopt: ask clip().
  std::optional<Cell> unclipped_end(const Eigen::Vector2d& point) const {
    if (origin_inside_ && inside(point) && (point - origin_).squaredNorm() < max_length_sq_)
      return g_.world_to_cell(point.x(), point.y());
    return std::nullopt;
  }
  // unclipped_end for many returns at once: for each of `n` points (map frame), kNoCell when it is
  // not finite or farther than sqrt(range_sq) from `origin` (3D, in double; origin.head<2>() is
  // the clipper's origin), else the grid index of unclipped_end(p.xy) when that gives a cell, else
  // kClipCell (ask clip). Four points at a time where the CPU has AVX2, with the same arithmetic.
  void end_cells(const Eigen::Vector3f* points, std::size_t n, const Eigen::Vector3d& origin, double range_sq,
                 std::int32_t* out) const;
  // The origin's cell (valid when unclipped_end or clip gave a ray).
  Cell start() const { return start_.value_or(Cell{}); }

 private:
  bool inside(const Eigen::Vector2d& q) const {
    return (q.array() >= lo_.array()).all() && (q.array() <= hi_.array()).all();
  }
  GridGeometry g_;
  Eigen::Vector2d origin_, lo_, hi_;  // the box shrunk by a hair (see clip)
  double max_length_m_;
  double max_length_sq_;  // with a margin for the square root's rounding (see clip)
  std::optional<Cell> start_;
  bool origin_inside_ = false;
};

}  // namespace bipednav::mapping
