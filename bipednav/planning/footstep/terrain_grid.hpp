#pragma once

#include <cstdint>
#include <vector>

#include "bipednav/mapping/heightmap.hpp"

namespace bipednav::footstep {

// The heightmap pooled onto the planner's lattice: per lattice cell the max, min and mean of
// the known heightmap cells inside it. Cells with no known height are unknown, which the
// planner treats as free (section VII: planning into unknown areas).
class TerrainGrid {
 public:
  TerrainGrid() = default;
  // `cell_m` is the lattice resolution; it is raised to the heightmap's if that is coarser.
  TerrainGrid(const mapping::Heightmap& map, double cell_m);

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

 private:
  std::size_t idx(int x, int y) const { return geometry_.index(x, y); }

  mapping::GridGeometry geometry_;
  std::vector<float> max_, min_, mean_;
  std::vector<std::uint16_t> count_;
  void build_sparse_table();
  // Level l holds, per cell, the summary of the 2^l x 2^l square starting there (clipped).
  // One entry per cell, its fields together: a query reads a few squares, one line each.
  struct Square {
    float max_h, min_h;
    bool all_known;
  };
  using Level = std::vector<Square>;
  std::vector<Level> levels_;
};

}  // namespace bipednav::footstep
