#include "bipednav/sim/terrain_truth.hpp"

#include <cmath>
#include <vector>

namespace bipednav::sim {

mapping::Heightmap true_heightmap(const RayCaster& caster, const mapping::GridGeometry& geometry, double top_z_m) {
  require(std::isfinite(top_z_m), "top_z_m", "finite");
  require(geometry.size() > 0, "geometry", "a non-empty grid");
  mapping::Heightmap map(geometry);
  const Eigen::Vector3f down(0.0f, 0.0f, -1.0f);
  const float range = static_cast<float>(top_z_m + 100.0);
  for (int y = 0; y < geometry.height; ++y) {
    for (int x = 0; x < geometry.width; ++x) {
      const Eigen::Vector2d c = geometry.cell_center(x, y);
      const float r = caster.cast(Eigen::Vector3d(c.x(), c.y(), top_z_m), down.cast<double>(), range);
      if (std::isfinite(r)) map.set(x, y, static_cast<float>(top_z_m - r), 0.0f);
    }
  }
  return map;
}

}  // namespace bipednav::sim
