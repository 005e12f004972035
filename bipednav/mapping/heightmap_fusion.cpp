#include "bipednav/mapping/heightmap_fusion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bipednav/common/error.hpp"

namespace bipednav::mapping {

void HeightmapFusionParams::validate() const {
  auto pos = [](double v) { return std::isfinite(v) && v > 0.0; };
  require(pos(variance_per_m2), "variance_per_m2", "> 0 m^2 per m^2");
  require(pos(min_observation_variance_m2), "min_observation_variance_m2", "> 0 m^2");
  require(pos(min_cell_variance_m2), "min_cell_variance_m2", "> 0 m^2");
  require(pos(max_cell_variance_m2) && max_cell_variance_m2 >= min_cell_variance_m2, "max_cell_variance_m2",
          ">= min_cell_variance_m2");
  require(pos(gate_sigma), "gate_sigma", "> 0");
  require(std::isfinite(variance_growth_factor) && variance_growth_factor > 1.0, "variance_growth_factor", "> 1");
  require(pos(max_range_m), "max_range_m", "> 0 m");
}

namespace {

// The parameters of fuse_height() in the float arithmetic of the map.
struct FuseConstants {
  float min_var, max_var, gate_sq, growth;
  explicit FuseConstants(const HeightmapFusionParams& p)
      : min_var(static_cast<float>(p.min_cell_variance_m2)),
        max_var(static_cast<float>(p.max_cell_variance_m2)),
        gate_sq(static_cast<float>(p.gate_sigma * p.gate_sigma)),
        growth(static_cast<float>(p.variance_growth_factor)) {}
};

inline FuseResult fuse(float& h, float& var, float z, float var_z, const FuseConstants& k) {
  if (!std::isfinite(h) || !std::isfinite(var)) {
    h = z;
    var = std::max(var_z, k.min_var);
    return FuseResult::kInitialised;
  }
  const float innovation = z - h;
  const float s = var + var_z;
  if (innovation * innovation > k.gate_sq * s) {
    var = std::min(var * k.growth, k.max_var);
    return FuseResult::kRejected;
  }
  // eq. 2: h <- (var_z h + var z) / (var + var_z);  eq. 3: var <- var_z var / (var + var_z)
  const float inv_s = 1.0f / s;
  h = (var_z * h + var * z) * inv_s;
  var = std::max(var_z * var * inv_s, k.min_var);
  return FuseResult::kFused;
}

}  // namespace

FuseResult fuse_height(float& h, float& var, float z, float var_z, const HeightmapFusionParams& p) {
  return fuse(h, var, z, var_z, FuseConstants(p));
}

HeightmapFusion::HeightmapFusion(const GridGeometry& geometry, const HeightmapFusionParams& params)
    : params_(params), map_(geometry) {
  params.validate();
  require(geometry.width > 0 && geometry.height > 0, "geometry.width/height", "> 0 cells");
  require(std::isfinite(geometry.resolution_m) && geometry.resolution_m > 0.0, "geometry.resolution_m", "> 0 m");
  bins_.assign(geometry.size(), Bin{-std::numeric_limits<float>::infinity(), 0.0f});
}

HeightmapUpdateStats HeightmapFusion::update(const std::vector<Eigen::Vector3f>& points_world,
                                             const Eigen::Vector3d& sensor_world) {
  HeightmapUpdateStats stats;
  if (!sensor_world.allFinite()) throw Error("heightmap update: sensor origin is not finite");
  const GridGeometry& g = map_.geometry();
  const float ox = static_cast<float>(g.origin_x_m), oy = static_cast<float>(g.origin_y_m);
  const float inv_res = static_cast<float>(1.0 / g.resolution_m);
  const Eigen::Vector3f s = sensor_world.cast<float>();
  const float max_d2 = static_cast<float>(params_.max_range_m * params_.max_range_m);
  // Binning: the highest point per cell is the cell's observation z_c. bins_[].z is -inf between
  // updates, so no per-update reset is needed; touched cells are reset while fusing below.
  int x0 = g.width, y0 = g.height, x1 = -1, y1 = -1;
  std::size_t used = 0;
  Bin* bins = bins_.data();
  for (const auto& p : points_world) {
    const float fx = (p.x() - ox) * inv_res, fy = (p.y() - oy) * inv_res;
    // Also false for NaN, so non-finite points drop out here.
    if (!(fx >= 0.0f && fy >= 0.0f && fx < float(g.width) && fy < float(g.height) && std::isfinite(p.z()))) continue;
    const float d2 = (p - s).squaredNorm();
    if (d2 > max_d2) continue;
    ++used;
    const int cx = static_cast<int>(fx), cy = static_cast<int>(fy);
    x0 = std::min(x0, cx);
    x1 = std::max(x1, cx);
    y0 = std::min(y0, cy);
    y1 = std::max(y1, cy);
    const std::size_t i = g.index(cx, cy);
    if (p.z() > bins[i].z) bins[i] = {p.z(), d2};
  }
  auto& h = map_.heights();
  auto& v = map_.variances();
  const float k = static_cast<float>(params_.variance_per_m2);
  const float vmin = static_cast<float>(params_.min_observation_variance_m2);
  constexpr float kNone = -std::numeric_limits<float>::infinity();
  const FuseConstants fk(params_);
  std::size_t rejected = 0, fused = 0;
  stats.points_used = used;
  for (int y = y0; y <= y1; ++y) {
    for (std::size_t i = g.index(x0, y), end = g.index(x1, y); i <= end; ++i) {
      if (bins[i].z == kNone) continue;
      const float var_z = std::max(k * bins[i].d2, vmin);
      const FuseResult r = fuse(h[i], v[i], bins[i].z, var_z, fk);
      rejected += r == FuseResult::kRejected;
      fused += r != FuseResult::kRejected;
      bins[i].z = kNone;
    }
  }
  stats.cells_rejected = rejected;
  stats.cells_fused = fused;
  return stats;
}

FootprintHeights footprint_heights(const Heightmap& map, const Pose2& center, double length_m, double width_m) {
  if (!center.is_finite() || !(length_m >= 0.0) || !(width_m >= 0.0))
    throw Error("footprint_heights: non-finite pose or negative footprint size");
  const GridGeometry& g = map.geometry();
  const double c = std::cos(center.theta), s = std::sin(center.theta);
  const double hl = 0.5 * length_m, hw = 0.5 * width_m;
  const double ex = std::abs(c) * hl + std::abs(s) * hw, ey = std::abs(s) * hl + std::abs(c) * hw;
  const auto lo = g.world_to_cell_unbounded(center.x - ex, center.y - ey);
  const auto hi = g.world_to_cell_unbounded(center.x + ex, center.y + ey);
  FootprintHeights out;
  out.min_m = std::numeric_limits<float>::infinity();
  out.max_m = -std::numeric_limits<float>::infinity();
  const double eps = 1e-9;
  for (int y = std::max(lo->y, 0); y <= std::min(hi->y, g.height - 1); ++y) {
    for (int x = std::max(lo->x, 0); x <= std::min(hi->x, g.width - 1); ++x) {
      const Eigen::Vector2d w = g.cell_center(x, y) - center.position();
      const double lx = c * w.x() + s * w.y(), ly = -s * w.x() + c * w.y();
      if (std::abs(lx) > hl + eps || std::abs(ly) > hw + eps) continue;
      ++out.cells;
      if (!map.known(x, y)) continue;
      ++out.known_cells;
      out.min_m = std::min(out.min_m, map.height(x, y));
      out.max_m = std::max(out.max_m, map.height(x, y));
    }
  }
  if (out.known_cells == 0) out.min_m = out.max_m = std::numeric_limits<float>::quiet_NaN();
  return out;
}

}  // namespace bipednav::mapping
