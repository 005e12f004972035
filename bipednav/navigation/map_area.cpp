#include "bipednav/navigation/map_area.hpp"

#include <cmath>

#include "bipednav/common/error.hpp"

namespace bipednav::navigation {

void MapArea::validate() const {
  require(std::isfinite(min_x_m) && std::isfinite(max_x_m) && min_x_m < max_x_m, "map area min_x_m/max_x_m",
          "finite, min_x_m < max_x_m");
  require(std::isfinite(min_y_m) && std::isfinite(max_y_m) && min_y_m < max_y_m, "map area min_y_m/max_y_m",
          "finite, min_y_m < max_y_m");
  require(std::isfinite(margin_m) && margin_m >= 0.0, "map area margin_m", ">= 0");
}

mapping::GridGeometry global_grid_for(const MapArea& area, double resolution_m) {
  area.validate();
  require(std::isfinite(resolution_m) && resolution_m > 0.0, "global map resolution_m", "> 0");
  const double res = resolution_m;
  const double origin_x_m = std::floor((area.min_x_m - area.margin_m) / res) * res;
  const double origin_y_m = std::floor((area.min_y_m - area.margin_m) / res) * res;
  const double cells_x = std::ceil((area.max_x_m + area.margin_m - origin_x_m) / res);
  const double cells_y = std::ceil((area.max_y_m + area.margin_m - origin_y_m) / res);
  // The bound keeps the conversion to int defined; a grid near it would not fit in memory anyway.
  constexpr double kMaxCellsPerSide = 1e6;
  require(cells_x <= kMaxCellsPerSide && cells_y <= kMaxCellsPerSide, "map area",
          "at most a million cells a side at the global map's resolution");
  mapping::GridGeometry g;
  g.resolution_m = res;
  g.origin_x_m = origin_x_m;
  g.origin_y_m = origin_y_m;
  g.width = static_cast<int>(cells_x);
  g.height = static_cast<int>(cells_y);
  return g;
}

}  // namespace bipednav::navigation
