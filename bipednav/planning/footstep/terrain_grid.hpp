#pragma once

#include <cstdint>
#include <vector>

#include "bipednav/mapping/heightmap.hpp"

namespace bipednav::planning::footstep {

// The heightmap pooled onto the planner's lattice: per lattice cell the max, min and mean of
// the known heightmap cells inside it. Cells with no known height are unknown, which the
// planner treats as free (section VII: planning into unknown areas).
class TerrainGrid {
 public:
  TerrainGrid() = default;
  // `cell_m` is the lattice resolution; it is raised to the heightmap's if that is coarser.
  // `occlusion_rise_m` > 0 also marks occluded cells (occluded()).
  TerrainGrid(const mapping::Heightmap& map, double cell_m, double occlusion_rise_m = 0.0);

  const mapping::GridGeometry& geometry() const { return geometry_; }
  bool in_bounds(int x, int y) const { return geometry_.in_bounds(x, y); }
  bool known(int x, int y) const { return count_[idx(x, y)] > 0; }
  float max_h(int x, int y) const { return max_[idx(x, y)]; }
  float min_h(int x, int y) const { return min_[idx(x, y)]; }
  float mean_h(int x, int y) const { return mean_[idx(x, y)]; }

  // Exact summary of the cells in [x0, x1] x [y0, y1] (clipped to the grid): their max and min
  // height and whether all are known, from a 2D sparse table of power-of-two squares (a few
  // lookups per query). Lets the planner accept flat, clear regions without a cell loop.
  struct RangeSummary {
    float max_h, min_h;
    bool all_known;
  };
  RangeSummary range(int x0, int y0, int x1, int y1) const;

  // Occluded cells: unknown cells 8-adjacent to a known cell that rises more than
  // `occlusion_rise_m` above a known 8-neighbour of its own. A rising face seen from the side
  // (a wall the head camera sees only the lower part of: nao_stairs' side wall reads 0.10-0.16 m
  // over the 0.10 m platform in its face cell, truly 0.60 m) hides what stands behind it, so the
  // unknown cells there may be arbitrarily high. None without a rise (the default).
  bool occluded(int x, int y) const { return !shadow_sum_.empty() && shadow_count(x, y, x, y) > 0; }
  bool any_occluded(int x0, int y0, int x1, int y1) const {
    return !shadow_sum_.empty() && shadow_count(x0, y0, x1, y1) > 0;
  }

 private:
  std::size_t idx(int x, int y) const { return geometry_.index(x, y); }

  mapping::GridGeometry geometry_;
  std::vector<float> max_, min_, mean_;
  std::vector<std::uint16_t> count_;
  void build_sparse_table();
  void mark_occluded(double rise_m);
  int shadow_count(int x0, int y0, int x1, int y1) const;
  std::vector<int> shadow_sum_;  // (w + 1) x (h + 1) summed-area table of occluded cells
  // Level l holds, per cell, the summary of the 2^l x 2^l square starting there (clipped).
  // One entry per cell, its fields together: a query reads a few squares, one line each.
  struct Square {
    float max_h, min_h;
    bool all_known;
  };
  using Level = std::vector<Square>;
  std::vector<Level> levels_;
};

}  // namespace bipednav::planning::footstep
