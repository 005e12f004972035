#include "bipednav/planning/footstep/terrain_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bipednav::planning::footstep {

TerrainGrid::TerrainGrid(const mapping::Heightmap& map, double cell_m, double occlusion_rise_m) {
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
  build_sparse_table();
  if (occlusion_rise_m > 0.0) mark_occluded(occlusion_rise_m);
}

void TerrainGrid::mark_occluded(double rise_m) {
  const int w = geometry_.width, h = geometry_.height;
  std::vector<std::uint8_t> shadow(geometry_.size(), 0);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (!known(x, y)) continue;
      // The lowest known 8-neighbour: does this cell rise above it (a face)?
      float low = std::numeric_limits<float>::infinity();
      bool next_to_unknown = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          if ((dx == 0 && dy == 0) || !in_bounds(x + dx, y + dy)) continue;
          if (known(x + dx, y + dy))
            low = std::min(low, min_h(x + dx, y + dy));
          else
            next_to_unknown = true;
        }
      if (!next_to_unknown || !(max_h(x, y) > low + rise_m)) continue;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if (in_bounds(x + dx, y + dy) && !known(x + dx, y + dy)) shadow[idx(x + dx, y + dy)] = 1;
    }
  }
  shadow_sum_.assign(static_cast<std::size_t>(w + 1) * (h + 1), 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      shadow_sum_[static_cast<std::size_t>(y + 1) * (w + 1) + (x + 1)] =
          shadow[idx(x, y)] + shadow_sum_[static_cast<std::size_t>(y) * (w + 1) + (x + 1)] +
          shadow_sum_[static_cast<std::size_t>(y + 1) * (w + 1) + x] -
          shadow_sum_[static_cast<std::size_t>(y) * (w + 1) + x];
}

int TerrainGrid::shadow_count(int x0, int y0, int x1, int y1) const {
  const int w = geometry_.width;
  x0 = std::max(x0, 0);
  y0 = std::max(y0, 0);
  x1 = std::min(x1, w - 1);
  y1 = std::min(y1, geometry_.height - 1);
  if (x0 > x1 || y0 > y1) return 0;
  const auto at = [&](int x, int y) { return shadow_sum_[static_cast<std::size_t>(y) * (w + 1) + x]; };
  return at(x1 + 1, y1 + 1) - at(x0, y1 + 1) - at(x1 + 1, y0) + at(x0, y0);
}

void TerrainGrid::build_sparse_table() {
  const int w = geometry_.width, h = geometry_.height;
  Level base(geometry_.size());
  for (std::size_t i = 0; i < geometry_.size(); ++i) {
    const bool k = count_[i] > 0;
    base[i] = {k ? max_[i] : -std::numeric_limits<float>::infinity(),
               k ? min_[i] : std::numeric_limits<float>::infinity(), k};
  }
  levels_.push_back(std::move(base));
  for (int s = 1; 2 * s <= std::max(w, h); s *= 2) {
    const Level& prev = levels_.back();
    Level next = prev;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        Square& q = next[idx(x, y)];
        for (const auto& [dx, dy] : {std::pair{s, 0}, {0, s}, {s, s}}) {
          if (x + dx >= w || y + dy >= h) continue;
          const Square& o = prev[idx(x + dx, y + dy)];
          q.max_h = std::max(q.max_h, o.max_h);
          q.min_h = std::min(q.min_h, o.min_h);
          q.all_known = q.all_known && o.all_known;
        }
      }
    }
    levels_.push_back(std::move(next));
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
  int level = 0;
  while ((2 << level) <= std::min(x1 - x0 + 1, y1 - y0 + 1) && level + 1 < static_cast<int>(levels_.size())) ++level;
  const int side = 1 << level;
  const Level& L = levels_[level];
  // Cover the rectangle with (overlapping) squares of the level's side.
  for (int yy = y0;; yy += side) {
    const int sy = std::min(yy, y1 - side + 1);
    for (int xx = x0;; xx += side) {
      const int sx = std::min(xx, x1 - side + 1);
      const Square& q = L[idx(sx, sy)];
      r.max_h = std::max(r.max_h, q.max_h);
      r.min_h = std::min(r.min_h, q.min_h);
      r.all_known = r.all_known && q.all_known;
      if (sx + side > x1) break;
    }
    if (sy + side > y1) break;
  }
  return r;
}

}  // namespace bipednav::planning::footstep
