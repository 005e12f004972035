#include "bipednav/mapping/obstacle_layer.hpp"

#include <cmath>

#include "bipednav/common/error.hpp"
#include "bipednav/mapping/ray_trace.hpp"

namespace bipednav::mapping {

void ObstacleLayerParams::validate() const {
  require(std::isfinite(obstacle_max_range_m) && obstacle_max_range_m > 0.0, "obstacle_max_range_m", "> 0 m");
  require(std::isfinite(raytrace_max_range_m) && raytrace_max_range_m >= 0.0, "raytrace_max_range_m", ">= 0 m");
}

ObstacleLayer::ObstacleLayer(const ObstacleLayerParams& params) : params_(params) { params.validate(); }

CellRect ObstacleLayer::update(Costmap2D& grid, const std::vector<Observation>& observations, bool allow_clearing) {
  CellRect changed;
  if (traced_.size() != grid.data().size()) {
    traced_.assign(grid.data().size(), 0);
    stamp_ = 0;
  }
  for (const auto& obs : observations)
    if (obs.clearing && allow_clearing) clear_observation(grid, obs, changed);
  for (const auto& obs : observations)
    if (obs.marking) mark_observation(grid, obs, changed);
  return changed;
}

void ObstacleLayer::clear_observation(Costmap2D& grid, const Observation& obs, CellRect& changed) {
  if (!obs.origin_map.allFinite()) return;
  if (++stamp_ == 0) {  // wrapped: forget all stamps
    std::fill(traced_.begin(), traced_.end(), 0);
    stamp_ = 1;
  }
  const GridGeometry& g = grid.geometry();
  const Eigen::Vector2d origin = obs.origin_map.head<2>();
  const double range = std::min(params_.raytrace_max_range_m, obs.max_range_m);
  const double max_range_sq = obs.max_range_m * obs.max_range_m;
  std::uint8_t* cells = grid.data().data();
  const RayClipper clipper(g, origin, range);  // origin cell and grid box once per observation
  for (const auto& p : obs.points_map) {
    if (!p.allFinite()) continue;
    if ((p.cast<double>() - obs.origin_map).squaredNorm() > max_range_sq) continue;
    const auto ray = clipper.clip(p.head<2>().cast<double>());
    if (!ray) continue;
    // Many returns share an end cell: trace each end cell once per observation.
    std::uint32_t& seen = traced_[g.index(ray->end)];
    if (seen == stamp_) continue;
    seen = stamp_;
    for_each_line_cell(ray->start, ray->end, ray->end_included, [&](int x, int y) {
      std::uint8_t& c = cells[g.index(x, y)];
      if (c != kFree) {
        c = kFree;
        changed.include(x, y);
      }
    });
  }
}

void ObstacleLayer::mark_observation(Costmap2D& grid, const Observation& obs, CellRect& changed) const {
  if (!obs.origin_map.allFinite()) return;
  const GridGeometry& g = grid.geometry();
  const double range = std::min(params_.obstacle_max_range_m, obs.max_range_m);
  const double range_sq = range * range;
  std::uint8_t* cells = grid.data().data();
  for (const auto& p : obs.points_map) {
    if (!p.allFinite()) continue;
    if ((p.cast<double>() - obs.origin_map).squaredNorm() > range_sq) continue;
    const auto c = g.world_to_cell(p.x(), p.y());
    if (!c) continue;
    std::uint8_t& v = cells[g.index(*c)];
    if (v != kLethal) {
      v = kLethal;
      changed.include(c->x, c->y);
    }
  }
}

}  // namespace bipednav::mapping
