#pragma once

#include <algorithm>
#include <climits>

#include "bipednav/mapping/grid_geometry.hpp"

namespace bipednav::mapping {

// A half-open rectangle of cells [x0, x1) x [y0, y1); used for dirty regions of layered updates.
struct CellRect {
  int x0 = INT_MAX;
  int y0 = INT_MAX;
  int x1 = INT_MIN;
  int y1 = INT_MIN;

  static CellRect all(const GridGeometry& g) { return {0, 0, g.width, g.height}; }
  bool empty() const { return x0 >= x1 || y0 >= y1; }
  int width() const { return empty() ? 0 : x1 - x0; }
  int height() const { return empty() ? 0 : y1 - y0; }
  bool contains(int x, int y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
  void include(int x, int y) {
    x0 = std::min(x0, x);
    y0 = std::min(y0, y);
    x1 = std::max(x1, x + 1);
    y1 = std::max(y1, y + 1);
  }
  void include(const CellRect& r) {
    if (r.empty()) return;
    include(r.x0, r.y0);
    include(r.x1 - 1, r.y1 - 1);
  }
  CellRect expanded(int r) const { return empty() ? *this : CellRect{x0 - r, y0 - r, x1 + r, y1 + r}; }
  CellRect clipped(const GridGeometry& g) const {
    if (empty()) return {};
    CellRect c{std::max(x0, 0), std::max(y0, 0), std::min(x1, g.width), std::min(y1, g.height)};
    return c.empty() ? CellRect{} : c;
  }
};

}  // namespace bipednav::mapping
