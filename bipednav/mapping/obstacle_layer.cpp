#include "bipednav/mapping/obstacle_layer.hpp"

#include <algorithm>
#include <cmath>

#include "bipednav/common/error.hpp"
#include "bipednav/mapping/ray_trace.hpp"

namespace bipednav::mapping {

void ObstacleLayerParams::validate() const {
  require(std::isfinite(obstacle_max_range_m) && obstacle_max_range_m > 0.0, "obstacle_max_range_m", "> 0 m");
  require(std::isfinite(raytrace_max_range_m) && raytrace_max_range_m >= 0.0, "raytrace_max_range_m", ">= 0 m");
}

ObstacleLayer::ObstacleLayer(const ObstacleLayerParams& params) : params_(params) { params.validate(); }

void ObstacleLayer::follow(const Costmap2D& grid) {
  const GridGeometry& g = grid.geometry();
  GridGeometry& b = band_geometry_;
  if (b.width != g.width || b.height != g.height || b.resolution_m != g.resolution_m || bands_.size() != g.size()) {
    bands_.assign(g.size(), HeightBand{});
  } else {
    const double dxf = (g.origin_x_m - b.origin_x_m) / g.resolution_m,
                 dyf = (g.origin_y_m - b.origin_y_m) / g.resolution_m;
    const double dx = std::round(dxf), dy = std::round(dyf);
    if (std::abs(dxf - dx) > 1e-6 || std::abs(dyf - dy) > 1e-6 || std::abs(dx) >= g.width || std::abs(dy) >= g.height)
      bands_.assign(g.size(), HeightBand{});
    else
      shift_cells(bands_, g, static_cast<int>(dx), static_cast<int>(dy), HeightBand{});
  }
  b = g;
}

const HeightBand& ObstacleLayer::band(int x, int y) const {
  static const HeightBand none;
  return band_geometry_.in_bounds(x, y) && bands_.size() == band_geometry_.size() ? bands_[band_geometry_.index(x, y)]
                                                                                  : none;
}

void ObstacleLayer::include_band(const Costmap2D& grid, int x, int y, const HeightBand& b, bool reset) {
  if (!params_.height_aware_clearing) return;  // no ray reads a band
  follow(grid);
  if (!grid.in_bounds(x, y)) return;
  HeightBand& mine = bands_[grid.geometry().index(x, y)];
  if (reset) mine = {};
  mine.include(b);
}

CellRect ObstacleLayer::update(Costmap2D& grid, const std::vector<Observation>& observations, bool allow_clearing) {
  CellRect changed;
  // Without height-aware clearing every band would stay empty: no bands are kept, moved or reset.
  if (params_.height_aware_clearing) follow(grid);
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
  // A ray crosses a cell within about half a cell diagonal of the cell centre's projection.
  const double half_cell = 0.71 * g.resolution_m;
  const bool bands = params_.height_aware_clearing;
  for (const auto& p : obs.points_map) {
    if (!p.allFinite()) continue;
    const Eigen::Vector3d d = p.cast<double>() - obs.origin_map;
    if (d.squaredNorm() > max_range_sq) continue;
    // Most returns lie on the grid within range: their end cell without the clipping (inline).
    const Eigen::Vector2d q = p.head<2>().cast<double>();
    std::optional<ClippedRay> ray;
    if (const auto end = clipper.unclipped_end(q))
      ray = ClippedRay{clipper.start(), *end, false};
    else
      ray = clipper.clip(q);
    if (!ray) continue;
    // Many returns share an end cell: trace each end cell once per observation. (A ray to the same
    // end at another height might free an obstacle this one passed over; it waits for the next update.)
    std::uint32_t& seen = traced_[g.index(ray->end)];
    if (seen == stamp_) continue;
    seen = stamp_;
    for_each_line_cell(ray->start, ray->end, ray->end_included, [&](int x, int y) {
      const std::size_t i = g.index(x, y);
      std::uint8_t& c = cells[i];
      if (c == kFree) return;
      if (bands && c == kLethal && !bands_[i].empty()) {
        // The ray's heights across the cell: its height where it passes the cell centre, give or
        // take half a cell diagonal of horizontal travel.
        const double len2 = d.head<2>().squaredNorm();  // only here: most rays meet no band
        const double inv_len = len2 > 0.0 ? 1.0 / std::sqrt(len2) : 0.0;
        const double s = (g.cell_center(x, y) - origin).dot(d.head<2>()) * inv_len;  // metres along the ray
        const double slope = d.z() * inv_len;
        const double z0 = obs.origin_map.z() + slope * (s - half_cell),
                     z1 = obs.origin_map.z() + slope * (s + half_cell);
        if (std::max(z0, z1) < bands_[i].lo || std::min(z0, z1) > bands_[i].hi) return;
      }
      c = kFree;
      changed.include(x, y);
    });
  }
}

void ObstacleLayer::mark_observation(Costmap2D& grid, const Observation& obs, CellRect& changed) {
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
    const std::size_t i = g.index(*c);
    std::uint8_t& v = cells[i];
    const bool fresh = v != kLethal;
    if (fresh) {
      v = kLethal;
      changed.include(c->x, c->y);
    }
    if (!params_.height_aware_clearing) continue;
    if (fresh) {
      bands_[i] = {};  // a new obstacle: the heights of the cell's old obstacles do not count
      if (obs.keep_heights) bands_[i].include(p.z());
    } else if (!obs.keep_heights) {
      bands_[i] = {};  // heights not known (a moving obstacle's): any ray clears the cell
    } else if (!bands_[i].empty()) {
      bands_[i].include(p.z());
    }
  }
}

}  // namespace bipednav::mapping
