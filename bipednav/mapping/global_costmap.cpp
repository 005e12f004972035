#include "bipednav/mapping/global_costmap.hpp"

#include <algorithm>
#include <cmath>

#include "bipednav/common/error.hpp"

namespace bipednav::mapping {

UnknownCostMode parse_unknown_cost_mode(const std::string& name) {
  if (name == "free") return UnknownCostMode::kFree;
  if (name == "unknown") return UnknownCostMode::kUnknown;
  if (name == "lethal") return UnknownCostMode::kLethal;
  throw ParamError("unknown_cost_mode", "one of free, unknown, lethal (got '" + name + "')");
}

void GlobalCostmapParams::validate() const {
  require(std::isfinite(resolution_m) && resolution_m > 0.0 && resolution_m <= 5.0, "resolution_m", "in (0, 5] m");
  require(std::isfinite(default_size_m) && default_size_m > resolution_m && default_size_m / resolution_m <= 20000.0,
          "default_size_m", "> resolution_m and <= 20000 cells across");
  require(std::isfinite(rate_hz) && rate_hz > 0.0, "rate_hz", "> 0 Hz");
  parse_unknown_cost_mode(unknown_cost_mode);
  inflation().validate();
  obstacle_layer().validate();
}

GridGeometry GlobalCostmap::default_geometry(const Pose2& start, const GlobalCostmapParams& params) {
  params.validate();
  if (!start.is_finite()) throw Error("global costmap: start pose is not finite");
  const double res = params.resolution_m;
  const int n = static_cast<int>(std::lround(params.default_size_m / res));
  return {n, n, res, (std::floor(start.x / res) - n / 2) * res, (std::floor(start.y / res) - n / 2) * res};
}

namespace {
const GridGeometry& checked(const GridGeometry& g) {
  require(g.width > 0 && g.height > 0 && g.size() <= 400'000'000u, "geometry.width/height", "> 0 and <= 4e8 cells");
  require(std::isfinite(g.resolution_m) && g.resolution_m > 0.0, "geometry.resolution_m", "> 0 m");
  require(std::isfinite(g.origin_x_m) && std::isfinite(g.origin_y_m), "geometry.origin", "finite");
  return g;
}
}  // namespace

GlobalCostmap::GlobalCostmap(const GridGeometry& geometry, const GlobalCostmapParams& params)
    : params_((params.validate(), params)),
      unknown_mode_(params.unknown_mode()),
      obstacle_layer_(params.obstacle_layer()),
      inflator_(params.inflation(), checked(geometry).resolution_m),
      occupancy_(geometry, kUnknown),
      costmap_(geometry, kFree),
      next_(geometry, kFree) {
  refresh(CellRect::all(geometry));
}

ChangeSet GlobalCostmap::update(const Pose2& T_map_base, const std::vector<Observation>& lidar_obs,
                                const LocalCostmap* local) {
  if (!T_map_base.is_finite()) throw Error("global costmap: robot pose is not finite");
  CellRect dirty;
  dirty.include(obstacle_layer_.update(occupancy_, lidar_obs, params_.lidar_clearing));
  if (local && params_.merge_local) dirty.include(merge_local(*local));
  return refresh(dirty);
}

CellRect GlobalCostmap::merge_local(const LocalCostmap& local) {
  const GridGeometry& g = occupancy_.geometry();
  const GridGeometry& lg = local.geometry();
  // Global cells under the local window.
  const auto lo =
      g.world_to_cell_unbounded(lg.origin_x_m + 0.5 * lg.resolution_m, lg.origin_y_m + 0.5 * lg.resolution_m);
  const auto hi = g.world_to_cell_unbounded(lg.origin_x_m + lg.size_x_m() - 0.5 * lg.resolution_m,
                                            lg.origin_y_m + lg.size_y_m() - 0.5 * lg.resolution_m);
  CellRect changed;
  if (!lo || !hi) return changed;
  const CellRect win = CellRect{lo->x, lo->y, hi->x + 1, hi->y + 1}.clipped(g);
  if (win.empty()) return changed;
  merge_.assign(static_cast<std::size_t>(win.width()) * win.height(), 0);
  const bool bands = obstacle_layer_.keeps_marks();  // otherwise there are no bands or ages to carry
  if (bands) {
    merge_bands_.assign(merge_.size(), HeightBand{});
    merge_used_.assign(merge_.size(), 1.0f);
  }
  const auto& seen = local.observed();
  const int local_life = local.params().obstacle_layer().mark_lifetime_updates;
  for (int y = 0; y < lg.height; ++y) {
    for (int x = 0; x < lg.width; ++x) {
      const std::uint8_t v = seen.cost(x, y);
      if (v == kUnknown) continue;
      const Eigen::Vector2d w = lg.cell_center(x, y);
      const auto c = g.world_to_cell(w.x(), w.y());
      if (!c || !win.contains(c->x, c->y)) continue;
      const std::size_t k = static_cast<std::size_t>(c->y - win.y0) * win.width() + (c->x - win.x0);
      merge_[k] |= v == kLethal ? 2 : 1;
      if (bands && v == kLethal) {
        merge_bands_[k].include(local.obstacle_band(x, y));
        // The global mark is as old as the local one (in shares of the lifetimes, as the two maps
        // update at different rates): a mark the local map has been ageing gets no second lifetime.
        const int age = local.mark_age(x, y);
        const float used = local_life > 0 && age > 0 ? static_cast<float>(age) / local_life : 0.0f;
        merge_used_[k] = std::min(merge_used_[k], used);
      }
    }
  }
  for (int y = win.y0; y < win.y1; ++y) {
    for (int x = win.x0; x < win.x1; ++x) {
      const std::size_t k = static_cast<std::size_t>(y - win.y0) * win.width() + (x - win.x0);
      const std::uint8_t f = merge_[k];
      if (f == 0) continue;
      const std::uint8_t target = (f & 2) ? kLethal : kFree;
      // The local obstacle's heights come along, so the global LiDAR rays clear it only where
      // they cross those heights.
      if (bands && target == kLethal)
        obstacle_layer_.include_band(occupancy_, x, y, merge_bands_[k], occupancy_.cost(x, y) != kLethal,
                                     merge_used_[k]);
      if (occupancy_.cost(x, y) != target) {
        occupancy_.set_cost(x, y, target);
        changed.include(x, y);
      }
    }
  }
  return changed;
}

ChangeSet GlobalCostmap::set_occupancy(const Costmap2D& prior) {
  const GridGeometry& g = occupancy_.geometry();
  if (prior.width() != g.width || prior.height() != g.height)
    throw Error("global costmap: prior map is " + std::to_string(prior.width()) + " x " +
                std::to_string(prior.height()) + " cells, the costmap " + std::to_string(g.width) + " x " +
                std::to_string(g.height));
  auto& occ = occupancy_.data();
  const auto& src = prior.data();
  for (std::size_t i = 0; i < occ.size(); ++i)
    occ[i] = src[i] == kLethal ? kLethal : (src[i] == kUnknown ? kUnknown : kFree);
  obstacle_layer_.forget_marks();  // a known map's obstacles do not decay
  return refresh(CellRect::all(g));
}

ChangeSet GlobalCostmap::clear() {
  occupancy_.fill(kUnknown);
  obstacle_layer_.forget_marks();
  return refresh(CellRect::all(occupancy_.geometry()));
}

ChangeSet GlobalCostmap::refresh(const CellRect& dirty) {
  const GridGeometry& g = occupancy_.geometry();
  // Final costs depend on obstacles at most radius_cells() away: recompute that neighbourhood.
  const CellRect region = dirty.expanded(inflator_.radius_cells()).clipped(g);
  ChangeSet changes;
  if (region.empty()) return changes;
  inflator_.inflate(occupancy_, next_, region);
  const std::uint8_t unknown_cost = unknown_mode_ == UnknownCostMode::kUnknown
                                        ? kUnknown
                                        : (unknown_mode_ == UnknownCostMode::kLethal ? kLethal : kFree);
  auto& out = costmap_.data();
  auto& nxt = next_.data();
  const auto& occ = occupancy_.data();
  for (int y = region.y0; y < region.y1; ++y) {
    for (int x = region.x0; x < region.x1; ++x) {
      const std::size_t i = g.index(x, y);
      std::uint8_t c = nxt[i];
      if (occ[i] == kUnknown && c < kInscribed && unknown_mode_ != UnknownCostMode::kFree) c = unknown_cost;
      if (c != out[i]) {
        changes.push_back({Cell{x, y}, out[i], c});
        out[i] = c;
      }
    }
  }
  return changes;
}

}  // namespace bipednav::mapping
