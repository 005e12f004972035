#include "bipednav/mapping/costmap2d.hpp"

#include <cmath>

#include "bipednav/common/error.hpp"

namespace bipednav::mapping {

void Costmap2D::shift_origin(double new_origin_x_m, double new_origin_y_m, std::uint8_t fill) {
  const double res = geometry_.resolution_m;
  const int dx = static_cast<int>(std::floor((new_origin_x_m - geometry_.origin_x_m) / res + 0.5));
  const int dy = static_cast<int>(std::floor((new_origin_y_m - geometry_.origin_y_m) / res + 0.5));
  if (dx == 0 && dy == 0) return;
  shift_cells(cost_, geometry_, dx, dy, fill);
  geometry_.origin_x_m += dx * res;
  geometry_.origin_y_m += dy * res;
}

ChangeSet diff(const Costmap2D& before, const Costmap2D& after) {
  const auto& a = before.geometry();
  const auto& b = after.geometry();
  if (a.width != b.width || a.height != b.height) throw Error("costmap diff: grids differ in size");
  ChangeSet out;
  for (std::size_t i = 0; i < before.data().size(); ++i) {
    if (before.data()[i] != after.data()[i]) out.push_back({a.cell_of(i), before.data()[i], after.data()[i]});
  }
  return out;
}

}  // namespace bipednav::mapping
