#pragma once

#include <cstdint>
#include <vector>

#include "bipednav/mapping/grid_geometry.hpp"

namespace bipednav::mapping {

// Cost convention of ROS costmap_2d / Nav2.
inline constexpr std::uint8_t kFree = 0;
inline constexpr std::uint8_t kInscribed = 253;
inline constexpr std::uint8_t kLethal = 254;
inline constexpr std::uint8_t kUnknown = 255;

// Moves a row-major grid of cells by (dx, dy) whole cells: the cell (x, y) takes the value of
// (x + dx, y + dy), and cells shifted in from outside take `fill` (a rolling window's move).
template <typename T>
void shift_cells(std::vector<T>& cells, const GridGeometry& g, int dx, int dy, const T& fill) {
  if (dx == 0 && dy == 0) return;
  std::vector<T> shifted(cells.size(), fill);
  for (int y = 0; y < g.height; ++y) {
    const int sy = y + dy;
    if (sy < 0 || sy >= g.height) continue;
    for (int x = 0; x < g.width; ++x) {
      const int sx = x + dx;
      if (sx < 0 || sx >= g.width) continue;
      shifted[g.index(x, y)] = cells[g.index(sx, sy)];
    }
  }
  cells.swap(shifted);
}

// A changed cell: its coordinates and the cost before and after the update.
struct CellChange {
  Cell cell;
  std::uint8_t old_cost = 0;
  std::uint8_t new_cost = 0;
};
using ChangeSet = std::vector<CellChange>;

// A 2D grid of costs. Plain storage with world <-> cell conversions; layers and updates live
// in the classes that own a Costmap2D.
class Costmap2D {
 public:
  Costmap2D() = default;
  Costmap2D(const GridGeometry& geometry, std::uint8_t fill = kFree)
      : geometry_(geometry), cost_(geometry.size(), fill) {}

  const GridGeometry& geometry() const { return geometry_; }
  int width() const { return geometry_.width; }
  int height() const { return geometry_.height; }
  double resolution_m() const { return geometry_.resolution_m; }
  bool in_bounds(int x, int y) const { return geometry_.in_bounds(x, y); }

  std::uint8_t cost(int x, int y) const { return cost_[geometry_.index(x, y)]; }
  std::uint8_t cost(const Cell& c) const { return cost(c.x, c.y); }
  void set_cost(int x, int y, std::uint8_t c) { cost_[geometry_.index(x, y)] = c; }
  void set_cost(const Cell& cell, std::uint8_t c) { set_cost(cell.x, cell.y, c); }
  void fill(std::uint8_t c) { std::fill(cost_.begin(), cost_.end(), c); }

  const std::vector<std::uint8_t>& data() const { return cost_; }
  std::vector<std::uint8_t>& data() { return cost_; }

  // Moves the grid's origin, keeping the costs of cells that stay inside (rolling window);
  // newly exposed cells get `fill`. The origin is snapped to whole cells.
  void shift_origin(double new_origin_x_m, double new_origin_y_m, std::uint8_t fill);

 private:
  GridGeometry geometry_;
  std::vector<std::uint8_t> cost_;
};

// Cells whose cost differs between two grids of the same geometry (a brute-force diff).
ChangeSet diff(const Costmap2D& before, const Costmap2D& after);

}  // namespace bipednav::mapping
