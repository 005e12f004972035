#include "bipednav/navigation/obstacle_margin.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "bipednav/common/error.hpp"

namespace bipednav::navigation {

mapping::Heightmap inflate_obstacles(const mapping::Heightmap& map, double margin_m, double min_step_m) {
  require(std::isfinite(margin_m) && margin_m >= 0.0, "margin_m", "finite and >= 0");
  require(std::isfinite(min_step_m) && min_step_m > 0.0, "min_step_m", "finite and > 0");
  const mapping::GridGeometry& g = map.geometry();
  mapping::Heightmap out = map;
  const int r = static_cast<int>(std::floor(margin_m / g.resolution_m + 1e-9));
  if (r == 0) return out;
  for (int y = 0; y < g.height; ++y) {
    for (int x = 0; x < g.width; ++x) {
      if (!map.known(x, y)) continue;
      const float h = map.height(x, y);
      float low = std::numeric_limits<float>::infinity();
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if (g.in_bounds(x + dx, y + dy) && map.known(x + dx, y + dy)) low = std::min(low, map.height(x + dx, y + dy));
      if (h - low <= min_step_m) continue;
      for (int dy = -r; dy <= r; ++dy) {
        for (int dx = -r; dx <= r; ++dx) {
          if (dx * dx + dy * dy > r * r || !g.in_bounds(x + dx, y + dy)) continue;
          if (!out.known(x + dx, y + dy) || out.height(x + dx, y + dy) < h)
            out.set(x + dx, y + dy, h, map.variance(x, y));
        }
      }
    }
  }
  return out;
}

}  // namespace bipednav::navigation
