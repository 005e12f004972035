#include "bipednav/tracking/detections.hpp"

#include <cmath>
#include <string>

#include "bipednav/common/error.hpp"
#include "bipednav/tracking/cluster_measurement.hpp"
#include "bipednav/tracking/clustering.hpp"

namespace bipednav::tracking {

std::vector<Eigen::Vector3d> unexplained_points(const DetectionInput& in, const StaticStructure& static_cells,
                                                const TrackerParams& params) {
  const bool heights = !in.heights_m.empty();
  require(!heights || in.heights_m.size() == in.points_map.size(), "tracking detection heights_m",
          "empty or one per point (" + std::to_string(in.points_map.size()) + "), got " +
              std::to_string(in.heights_m.size()));
  std::vector<Eigen::Vector3d> out;
  if (!in.T_map_base.is_finite()) return out;
  const Eigen::Vector2d robot = in.T_map_base.position();
  const double r2 = params.max_range_m * params.max_range_m;
  for (std::size_t i = 0; i < in.points_map.size(); ++i) {
    const Eigen::Vector2d& p = in.points_map[i];
    const double z = heights ? in.heights_m[i] : 0.0;
    if (!p.allFinite() || !std::isfinite(z) || (p - robot).squaredNorm() > r2) continue;
    if (static_cells.near(p, params.static_margin_m, params.static_age_s)) continue;
    out.emplace_back(p.x(), p.y(), z);
  }
  return out;
}

std::vector<Detection> detect_objects(const DetectionInput& in, const StaticStructure& static_cells,
                                      const TrackerParams& params) {
  const std::vector<Eigen::Vector3d> points = unexplained_points(in, static_cells, params);
  std::vector<Detection> out;
  for (const auto& members : euclidean_clusters(points, params.cluster_cell_m, params.min_cluster_points)) {
    const Detection d = measure_cluster(points, members, in.T_map_base.position(), params);
    if (d.radius_m <= params.max_cluster_radius_m && d.finite()) out.push_back(d);
  }
  return out;
}

}  // namespace bipednav::tracking
