#include "bipednav/mapping/local_costmap.hpp"

#include <cmath>

#include "bipednav/common/error.hpp"

namespace bipednav::mapping {

void LocalCostmapParams::validate() const {
  require(std::isfinite(resolution_m) && resolution_m > 0.0 && resolution_m <= 1.0, "resolution_m", "in (0, 1] m");
  require(std::isfinite(size_m) && size_m >= 2.0 * resolution_m && size_m / resolution_m <= 4000.0, "size_m",
          ">= 2 cells and <= 4000 cells across");
  require(std::isfinite(rate_hz) && rate_hz > 0.0, "rate_hz", "> 0 Hz");
  inflation().validate();
  obstacle_layer().validate();
}

namespace {

GridGeometry window_geometry(const LocalCostmapParams& p) {
  p.validate();
  const int n = static_cast<int>(std::lround(p.size_m / p.resolution_m));
  return {n, n, p.resolution_m, -0.5 * n * p.resolution_m, -0.5 * n * p.resolution_m};
}

}  // namespace

LocalCostmap::LocalCostmap(const LocalCostmapParams& params)
    : params_(params),
      obstacle_layer_(params.obstacle_layer()),
      inflator_(params.inflation(), params.resolution_m),
      layer_(window_geometry(params), kUnknown),
      obstacles_(layer_.geometry(), kFree),
      costmap_(layer_.geometry(), kFree) {}

void LocalCostmap::recenter(const Pose2& T_map_base, Costmap2D& previous) {
  const GridGeometry& g = layer_.geometry();
  const double res = g.resolution_m;
  // Origins stay on the lattice of whole cells of the map frame, so shifting never resamples.
  const double ox = (std::floor(T_map_base.x / res) - g.width / 2) * res;
  const double oy = (std::floor(T_map_base.y / res) - g.height / 2) * res;
  if (!placed_) {
    GridGeometry ng = g;
    ng.origin_x_m = ox;
    ng.origin_y_m = oy;
    layer_ = Costmap2D(ng, kUnknown);
    obstacles_ = Costmap2D(ng, kFree);
    costmap_ = Costmap2D(ng, kFree);
    previous = costmap_;
    placed_ = true;
    return;
  }
  layer_.shift_origin(ox, oy, kUnknown);
  obstacles_.shift_origin(ox, oy, kFree);
  previous.shift_origin(ox, oy, kFree);
}

ChangeSet LocalCostmap::update(const Pose2& T_map_base, const std::vector<Observation>& observations) {
  if (!T_map_base.is_finite()) throw Error("local costmap: robot pose is not finite");
  Costmap2D previous = costmap_;
  recenter(T_map_base, previous);
  obstacle_layer_.update(layer_, observations);
  const auto& l = layer_.data();
  auto& o = obstacles_.data();
  for (std::size_t i = 0; i < l.size(); ++i) o[i] = l[i] == kLethal ? kLethal : kFree;
  costmap_ = Costmap2D(layer_.geometry(), kFree);
  inflator_.inflate(obstacles_, costmap_);
  return diff(previous, costmap_);
}

void LocalCostmap::clear() {
  layer_.fill(kUnknown);
  obstacles_.fill(kFree);
  costmap_.fill(kFree);
}

}  // namespace bipednav::mapping
