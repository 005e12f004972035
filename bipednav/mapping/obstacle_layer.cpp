#include "bipednav/mapping/obstacle_layer.hpp"

#include <algorithm>
#include <cmath>

#include "bipednav/common/error.hpp"
#include "bipednav/mapping/ray_trace.hpp"

namespace bipednav::mapping {

void ObstacleLayerParams::validate() const {
  require(std::isfinite(obstacle_max_range_m) && obstacle_max_range_m > 0.0, "obstacle_max_range_m", "> 0 m");
  require(std::isfinite(raytrace_max_range_m) && raytrace_max_range_m >= 0.0, "raytrace_max_range_m", ">= 0 m");
  require(mark_lifetime_updates >= 0, "mark_lifetime_updates", ">= 0 (0: marks never expire)");
}

int decay_updates(double decay_s, double rate_hz) {
  require(std::isfinite(decay_s) && decay_s >= 0.0 && decay_s <= 1e6, "mark_decay_s", "in [0, 1e6] s (0: never)");
  if (decay_s == 0.0 || !(rate_hz > 0.0) || !std::isfinite(rate_hz)) return 0;
  return static_cast<int>(std::clamp(std::ceil(decay_s * rate_hz), 1.0, 1e9));
}

ObstacleLayer::ObstacleLayer(const ObstacleLayerParams& params) : params_(params) { params.validate(); }

void ObstacleLayer::follow(const Costmap2D& grid) {
  const GridGeometry& g = grid.geometry();
  GridGeometry& b = band_geometry_;
  if (b.width != g.width || b.height != g.height || b.resolution_m != g.resolution_m || marks_.size() != g.size()) {
    marks_.assign(g.size(), Mark{});
  } else {
    const double dxf = (g.origin_x_m - b.origin_x_m) / g.resolution_m,
                 dyf = (g.origin_y_m - b.origin_y_m) / g.resolution_m;
    const double dx = std::round(dxf), dy = std::round(dyf);
    if (std::abs(dxf - dx) > 1e-6 || std::abs(dyf - dy) > 1e-6 || std::abs(dx) >= g.width || std::abs(dy) >= g.height)
      marks_.assign(g.size(), Mark{});
    else
      shift_cells(marks_, g, static_cast<int>(dx), static_cast<int>(dy), Mark{});
  }
  b = g;
}

const HeightBand& ObstacleLayer::band(int x, int y) const {
  static const HeightBand none;
  return band_geometry_.in_bounds(x, y) && marks_.size() == band_geometry_.size()
             ? marks_[band_geometry_.index(x, y)].band
             : none;
}

int ObstacleLayer::mark_age(int x, int y) const {
  if (!band_geometry_.in_bounds(x, y) || marks_.size() != band_geometry_.size()) return -1;
  const std::uint32_t c = marks_[band_geometry_.index(x, y)].confirmed;
  return c == kPermanent ? -1 : static_cast<int>(tick_ - c);
}

void ObstacleLayer::forget_marks() {
  for (auto& m : marks_) m = {};
}

void ObstacleLayer::include_band(const Costmap2D& grid, int x, int y, const HeightBand& b, bool reset) {
  if (!keeps_marks()) return;  // no ray reads a band, no mark decays
  follow(grid);
  if (!grid.in_bounds(x, y)) return;
  Mark& mine = marks_[grid.geometry().index(x, y)];
  if (reset) mine = {};
  if (params_.height_aware_clearing) mine.band.include(b);
  // Confirmed by the caller now (a permanent mark stays permanent). Before the first update
  // (tick 0) there is nothing to count from: the mark is confirmed at update 1.
  if (params_.mark_lifetime_updates > 0 && (reset || mine.confirmed != kPermanent))
    mine.confirmed = std::max(tick_, 1u);
}

CellRect ObstacleLayer::update(Costmap2D& grid, const std::vector<Observation>& observations, bool allow_clearing,
                               bool marks_expire) {
  CellRect changed;
  // Without height-aware clearing or decay no marks are kept, moved or reset (every band would stay empty).
  if (keeps_marks()) follow(grid);
  if (++tick_ == kPermanent) {  // wrapped (after 4e9 updates): every expiring mark counts as confirmed now
    tick_ = 1;
    for (auto& m : marks_)
      if (m.confirmed != kPermanent) m.confirmed = tick_;
  }
  if (traced_.size() != grid.data().size()) {
    traced_.assign(grid.data().size(), 0);
    stamp_ = 0;
  }
  for (const auto& obs : observations)
    if (obs.clearing && allow_clearing) clear_observation(grid, obs, changed);
  const std::uint32_t confirmed = marks_expire && params_.mark_lifetime_updates > 0 ? tick_ : kPermanent;
  for (const auto& obs : observations)
    if (obs.marking) mark_observation(grid, obs, confirmed, changed);
  if (params_.mark_lifetime_updates > 0) expire(grid, changed);
  return changed;
}

void ObstacleLayer::expire(Costmap2D& grid, CellRect& changed) {
  const GridGeometry& g = grid.geometry();
  std::uint8_t* cells = grid.data().data();
  const auto lifetime = static_cast<std::uint32_t>(params_.mark_lifetime_updates);
  for (int y = 0; y < g.height; ++y) {
    for (int x = 0; x < g.width; ++x) {
      const std::size_t i = g.index(x, y);
      if (cells[i] != kLethal) continue;
      Mark& m = marks_[i];
      if (m.confirmed == kPermanent || tick_ - m.confirmed <= lifetime) continue;
      cells[i] = kUnknown;  // no longer known: neither an obstacle nor seen free
      m = {};
      changed.include(x, y);
    }
  }
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
  const bool marks = keeps_marks();
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
      if (bands && c == kLethal && !marks_[i].band.empty()) {
        // The ray's heights across the cell: its height where it passes the cell centre, give or
        // take half a cell diagonal of horizontal travel.
        const double len2 = d.head<2>().squaredNorm();  // only here: most rays meet no band
        const double inv_len = len2 > 0.0 ? 1.0 / std::sqrt(len2) : 0.0;
        const double s = (g.cell_center(x, y) - origin).dot(d.head<2>()) * inv_len;  // metres along the ray
        const double slope = d.z() * inv_len;
        const double z0 = obs.origin_map.z() + slope * (s - half_cell),
                     z1 = obs.origin_map.z() + slope * (s + half_cell);
        if (std::max(z0, z1) < marks_[i].band.lo || std::min(z0, z1) > marks_[i].band.hi) return;
      }
      if (marks && c == kLethal) marks_[i] = {};  // nothing left to decay
      c = kFree;
      changed.include(x, y);
    });
  }
}

void ObstacleLayer::mark_observation(Costmap2D& grid, const Observation& obs, std::uint32_t confirmed,
                                     CellRect& changed) {
  if (!obs.origin_map.allFinite()) return;
  const GridGeometry& g = grid.geometry();
  const double range = std::min(params_.obstacle_max_range_m, obs.max_range_m);
  const double range_sq = range * range;
  std::uint8_t* cells = grid.data().data();
  const bool bands = params_.height_aware_clearing, decays = params_.mark_lifetime_updates > 0;
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
    if (decays) {
      // A fresh mark takes this update's stamp; a permanent one stays permanent.
      std::uint32_t& m = marks_[i].confirmed;
      if (fresh || m != kPermanent) m = confirmed;
    }
    if (!bands) continue;
    HeightBand& b = marks_[i].band;
    if (fresh) {
      b = {};  // a new obstacle: the heights of the cell's old obstacles do not count
      if (obs.keep_heights) b.include(p.z());
    } else if (!obs.keep_heights) {
      b = {};  // heights not known (a moving obstacle's): any ray clears the cell
    } else if (!b.empty()) {
      b.include(p.z());
    }
  }
}

}  // namespace bipednav::mapping
