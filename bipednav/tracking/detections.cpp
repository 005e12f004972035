#include "bipednav/tracking/detections.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "bipednav/common/error.hpp"
#include "bipednav/tracking/cluster_measurement.hpp"
#include "bipednav/tracking/clustering.hpp"

namespace bipednav::tracking {

std::vector<Eigen::Vector3d> points_in_range(const DetectionInput& in, const TrackerParams& params) {
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
    if (p.allFinite() && std::isfinite(z) && (p - robot).squaredNorm() <= r2) out.emplace_back(p.x(), p.y(), z);
  }
  return out;
}

std::vector<Eigen::Vector3d> unexplained_points(std::span<const Eigen::Vector3d> points,
                                                const StaticStructure& static_cells, const PersistentCells* persistent,
                                                std::span<const MoverCircle> movers, const TrackerParams& params) {
  std::vector<Eigen::Vector3d> out;
  for (const auto& p : points) {
    const Eigen::Vector2d q = p.head<2>();
    const bool on_mover =
        std::any_of(movers.begin(), movers.end(), [&](const MoverCircle& c) { return c.contains(q); });
    if (!on_mover && persistent != nullptr && persistent->persistent(q)) continue;
    if (!on_mover && static_cells.near(q, params.static_margin_m, params.static_age_s)) continue;
    out.push_back(p);
  }
  return out;
}

std::vector<Detection> detect_objects(std::span<const Eigen::Vector3d> unexplained, const Eigen::Vector2d& viewpoint,
                                      const TrackerParams& params, bool heights_known) {
  std::vector<Detection> out;
  for (const auto& members : euclidean_clusters(unexplained, params.cluster_cell_m, params.min_cluster_points)) {
    const Detection d = measure_cluster(unexplained, members, viewpoint, params, heights_known);
    if (d.radius_m <= params.max_cluster_radius_m && d.finite()) out.push_back(d);
  }
  return out;
}

}  // namespace bipednav::tracking
