#include "bipednav/planning/footstep/terrain_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bipednav::footstep {

TerrainGrid::TerrainGrid(const mapping::Heightmap& map, double cell_m) {
  const auto& g = map.geometry();
  const double res = std::max(cell_m, g.resolution_m);
  geometry_.resolution_m = res;
  geometry_.origin_x_m = g.origin_x_m;
  geometry_.origin_y_m = g.origin_y_m;
  geometry_.width = std::max(1, static_cast<int>(std::ceil(g.size_x_m() / res - 1e-9)));
  geometry_.height = std::max(1, static_cast<int>(std::ceil(g.size_y_m() / res - 1e-9)));
  const std::size_t n = geometry_.size();
  max_.assign(n, -std::numeric_limits<float>::infinity());
  min_.assign(n, std::numeric_limits<float>::infinity());
  mean_.assign(n, 0.0f);
  count_.assign(n, 0);
  std::vector<double> sum(n, 0.0);
  for (int y = 0; y < g.height; ++y) {
    for (int x = 0; x < g.width; ++x) {
      if (!map.known(x, y)) continue;
      const auto c = g.cell_center(x, y);
      const auto cell = geometry_.world_to_cell(c.x(), c.y());
      if (!cell) continue;
      const std::size_t i = geometry_.index(*cell);
      const float h = map.height(x, y);
      max_[i] = std::max(max_[i], h);
      min_[i] = std::min(min_[i], h);
      sum[i] += h;
      if (count_[i] < std::numeric_limits<std::uint16_t>::max()) ++count_[i];
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    if (count_[i] > 0) mean_[i] = static_cast<float>(sum[i] / count_[i]);
  tiles_x_ = (geometry_.width + kTile - 1) / kTile;
  tiles_y_ = (geometry_.height + kTile - 1) / kTile;
  const std::size_t nt = static_cast<std::size_t>(tiles_x_) * tiles_y_;
  tile_max_.assign(nt, -std::numeric_limits<float>::infinity());
  tile_min_.assign(nt, std::numeric_limits<float>::infinity());
  tile_known_.assign(nt, 1);
  for (int y = 0; y < geometry_.height; ++y) {
    for (int x = 0; x < geometry_.width; ++x) {
      const std::size_t t = static_cast<std::size_t>(y / kTile) * tiles_x_ + x / kTile;
      const std::size_t i = idx(x, y);
      if (count_[i] == 0) {
        tile_known_[t] = 0;
        continue;
      }
      tile_max_[t] = std::max(tile_max_[t], max_[i]);
      tile_min_[t] = std::min(tile_min_[t], min_[i]);
    }
  }
}

TerrainGrid::RangeSummary TerrainGrid::range(int x0, int y0, int x1, int y1) const {
  RangeSummary r{-std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(), true};
  x0 = std::max(x0, 0);
  y0 = std::max(y0, 0);
  x1 = std::min(x1, geometry_.width - 1);
  y1 = std::min(y1, geometry_.height - 1);
  if (x0 > x1 || y0 > y1) {
    r.all_known = false;
    return r;
  }
  for (int ty = y0 / kTile; ty <= y1 / kTile; ++ty) {
    for (int tx = x0 / kTile; tx <= x1 / kTile; ++tx) {
      const std::size_t t = static_cast<std::size_t>(ty) * tiles_x_ + tx;
      r.max_h = std::max(r.max_h, tile_max_[t]);
      r.min_h = std::min(r.min_h, tile_min_[t]);
      r.all_known = r.all_known && tile_known_[t];
    }
  }
  return r;
}

}  // namespace bipednav::footstep
