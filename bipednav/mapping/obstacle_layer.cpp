#include "bipednav/mapping/obstacle_layer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

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
  return marks_[band_geometry_.index(x, y)].passes;
}

void ObstacleLayer::forget_marks() {
  for (auto& m : marks_) m = {};
}

void ObstacleLayer::include_band(const Costmap2D& grid, int x, int y, const HeightBand& b, bool reset, double used) {
  if (!keeps_marks()) return;  // no ray reads a band, no mark decays
  follow(grid);
  if (!grid.in_bounds(x, y)) return;
  Mark& mine = marks_[grid.geometry().index(x, y)];
  if (reset) mine = {};
  if (params_.height_aware_clearing) mine.band.include(b);
  const int lifetime = params_.mark_lifetime_updates;
  if (lifetime == 0) return;
  const int passes = static_cast<int>(std::lround(std::clamp(std::isfinite(used) ? used : 1.0, 0.0, 1.0) * lifetime));
  if (reset) {
    mine.passes = passes;
    mine.counted = tick_;  // an update that passed the cell before it was set does not count
  } else if (mine.passes >= 0) {
    mine.passes = std::min(mine.passes, passes);
  }
}

CellRect ObstacleLayer::update(Costmap2D& grid, const std::vector<Observation>& observations, bool allow_clearing) {
  CellRect changed;
  // Without height-aware clearing or decay no marks are kept, moved or reset (every band would stay empty).
  if (keeps_marks()) follow(grid);
  ++tick_;  // only compared for equality (one count per update): wrapping is harmless
  if (traced_.size() != grid.data().size()) {
    traced_.assign(grid.data().size(), 0);
    stamp_ = 0;
  }
  for (const auto& obs : observations)
    if (obs.clearing && allow_clearing) clear_observation(grid, obs, changed);
  for (const auto& obs : observations)
    if (obs.marking) mark_observation(grid, obs, changed);
  if (params_.mark_lifetime_updates > 0) expire(grid, changed);
  return changed;
}

void ObstacleLayer::expire(Costmap2D& grid, CellRect& changed) {
  const GridGeometry& g = grid.geometry();
  std::uint8_t* cells = grid.data().data();
  const int lifetime = params_.mark_lifetime_updates;
  // The lethal cells in index (row-major) order, found by memchr: most cells are not lethal.
  const std::size_t n = g.width > 0 && g.height > 0 ? static_cast<std::size_t>(g.width) * g.height : 0;
  for (std::size_t i = 0; i < n; ++i) {
    const void* next = std::memchr(cells + i, kLethal, n - i);
    if (next == nullptr) break;
    i = static_cast<std::size_t>(static_cast<const std::uint8_t*>(next) - cells);
    Mark& m = marks_[i];
    if (m.passes <= lifetime) continue;  // also the permanent ones (-1)
    cells[i] = kUnknown;                 // no longer known: neither an obstacle nor seen free
    m = {};
    const Cell c = g.cell_of(i);
    changed.include(c.x, c.y);
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
  const bool marks = keeps_marks(), decays = params_.mark_lifetime_updates > 0;
  // Most returns lie on the grid within range: their end cells without the clipping, all at once.
  const std::size_t n = obs.points_map.size();
  codes_.resize(n);
  clipper.end_cells(obs.points_map.data(), n, obs.origin_map, max_range_sq, codes_.data());
  for (std::size_t k = 0; k < n; ++k) {
    const std::int32_t code = codes_[k];
    if (code == kNoCell) continue;  // not finite or out of range
    ClippedRay ray;
    if (code >= 0) {
      // Many returns share an end cell: trace each end cell once per observation. (A ray to the same
      // end at another height might free an obstacle this one passed over; it waits for the next update.)
      std::uint32_t& seen = traced_[static_cast<std::size_t>(code)];
      if (seen == stamp_) continue;
      seen = stamp_;
      ray = ClippedRay{clipper.start(), g.cell_of(static_cast<std::size_t>(code)), false};
    } else {
      const auto clipped = clipper.clip(obs.points_map[k].head<2>().cast<double>());
      if (!clipped) continue;
      ray = *clipped;
      std::uint32_t& seen = traced_[g.index(ray.end)];
      if (seen == stamp_) continue;
      seen = stamp_;
    }
    const Eigen::Vector3d d = obs.points_map[k].cast<double>() - obs.origin_map;
    for_each_line_index(ray.start, ray.end, ray.end_included, g.width, [&](std::size_t i, int x, int y) {
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
        Mark& m = marks_[i];
        if (std::max(z0, z1) < m.band.lo || std::min(z0, z1) > m.band.hi) {
          // Passed over or under: the sensor looked here and saw nothing at its heights (counted
          // once per update however many rays pass).
          if (decays && m.passes >= 0 && m.counted != tick_) {
            ++m.passes;
            m.counted = tick_;
          }
          return;
        }
      }
      if (marks && c == kLethal) marks_[i] = {};  // nothing left to decay
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
  const bool bands = params_.height_aware_clearing, decays = params_.mark_lifetime_updates > 0;
  const std::size_t n = obs.points_map.size();
  codes_.resize(n);
  point_cells(g, obs.points_map.data(), n, obs.origin_map, range_sq, codes_.data());
  for (std::size_t k = 0; k < n; ++k) {
    if (codes_[k] < 0) continue;  // not finite, out of range or off the grid
    const auto i = static_cast<std::size_t>(codes_[k]);
    const Eigen::Vector3f& p = obs.points_map[k];
    std::uint8_t& v = cells[i];
    const bool fresh = v != kLethal;
    if (fresh) {
      v = kLethal;
      const Cell c = g.cell_of(i);
      changed.include(c.x, c.y);
    }
    if (decays && (fresh || marks_[i].passes >= 0)) {
      // Confirmed now (after this update's rays: a pass and a return in one update is a return);
      // an obstacle someone else set (a prior map's) stays permanent.
      marks_[i].passes = 0;
      marks_[i].counted = tick_;
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
