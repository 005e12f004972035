#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <optional>

namespace bipednav::mapping {

// Integer cell coordinates (x = column, y = row; row 0 at the origin's y).
struct Cell {
  int x = 0;
  int y = 0;
  bool operator==(const Cell&) const = default;
};

// Geometry of a regular 2D grid: `origin` is the world position of cell (0, 0)'s lower-left corner.
struct GridGeometry {
  int width = 0;   // cells along x
  int height = 0;  // cells along y
  double resolution_m = 0.05;
  double origin_x_m = 0.0;
  double origin_y_m = 0.0;

  bool operator==(const GridGeometry&) const = default;
  std::size_t size() const { return static_cast<std::size_t>(width) * static_cast<std::size_t>(height); }
  bool in_bounds(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
  bool in_bounds(const Cell& c) const { return in_bounds(c.x, c.y); }
  std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * width + x; }
  std::size_t index(const Cell& c) const { return index(c.x, c.y); }
  Cell cell_of(std::size_t i) const { return {static_cast<int>(i % width), static_cast<int>(i / width)}; }

  // Cell containing a world point (may be out of bounds; NaN gives nullopt).
  std::optional<Cell> world_to_cell_unbounded(double wx, double wy) const {
    const double fx = std::floor((wx - origin_x_m) / resolution_m);
    const double fy = std::floor((wy - origin_y_m) / resolution_m);
    if (!std::isfinite(fx) || !std::isfinite(fy) || std::abs(fx) > 1e9 || std::abs(fy) > 1e9) return std::nullopt;
    return Cell{static_cast<int>(fx), static_cast<int>(fy)};
  }
  // Cell containing a world point, or nullopt when outside the grid.
  std::optional<Cell> world_to_cell(double wx, double wy) const {
    auto c = world_to_cell_unbounded(wx, wy);
    if (!c || !in_bounds(*c)) return std::nullopt;
    return c;
  }
  // World position of a cell's centre.
  Eigen::Vector2d cell_center(int x, int y) const {
    return {origin_x_m + (x + 0.5) * resolution_m, origin_y_m + (y + 0.5) * resolution_m};
  }
  Eigen::Vector2d cell_center(const Cell& c) const { return cell_center(c.x, c.y); }
  double size_x_m() const { return width * resolution_m; }
  double size_y_m() const { return height * resolution_m; }
};

}  // namespace bipednav::mapping
