// The clutter family (world_generator.hpp): a lattice of thin posts and boxes grown by a cellular
// automaton, between two walls, with the start before it and the goal beyond it.
#include <numbers>
#include <vector>

#include "bipednav/sim/world_layouts.hpp"
#include "bipednav/sim/world_parts.hpp"

namespace bipednav::sim {
namespace {

constexpr double kCell_m = 0.3;
constexpr int kSmoothingRounds = 3;
// A cell with at least kBirth filled neighbours (of 8) fills, one with at most kDeath empties, the
// rest keep their state (cells outside the lattice count as empty): sparse first draws thin out to
// scattered posts, dense ones grow into clumps with passages between them.
constexpr int kBirth = 5, kDeath = 1;

using Lattice = std::vector<std::vector<bool>>;  // [ix][iy]

int filled_neighbours(const Lattice& cells, int ix, int iy) {
  const int nx = static_cast<int>(cells.size()), ny = static_cast<int>(cells[0].size());
  int n = 0;
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy) {
      const int x = ix + dx, y = iy + dy;
      if ((dx != 0 || dy != 0) && x >= 0 && y >= 0 && x < nx && y < ny && cells[x][y]) ++n;
    }
  return n;
}

Lattice grow_lattice(Rng& rng, int nx, int ny, double fill) {
  Lattice cells(static_cast<std::size_t>(nx), std::vector<bool>(static_cast<std::size_t>(ny)));
  for (auto& column : cells)
    for (std::size_t iy = 0; iy < column.size(); ++iy) column[iy] = rng.bernoulli(fill);
  for (int round = 0; round < kSmoothingRounds; ++round) {
    Lattice next = cells;
    for (int ix = 0; ix < nx; ++ix)
      for (int iy = 0; iy < ny; ++iy) {
        const int n = filled_neighbours(cells, ix, iy);
        if (n >= kBirth) next[ix][iy] = true;
        if (n <= kDeath) next[ix][iy] = false;
      }
    cells = std::move(next);
  }
  return cells;
}

}  // namespace

LayoutDraft draw_clutter(Rng& rng, double fill) {
  LayoutDraft d;
  d.layout = "clutter";
  const int nx = static_cast<int>(rng.uniform_int(16, 20)), ny = static_cast<int>(rng.uniform_int(20, 26));
  const double wx = nx * kCell_m, field_y = ny * kCell_m;
  const double y_lo = -2.5, y_hi = field_y + 2.8;
  World& w = d.world;
  w.statics.push_back(wall_segment("wall_west", {0, y_lo}, {0, y_hi}));
  w.statics.push_back(wall_segment("wall_east", {wx, y_lo}, {wx, y_hi}));
  w.statics.push_back(wall_segment("wall_south", {0, y_lo}, {wx, y_lo}));
  w.statics.push_back(wall_segment("wall_north", {0, y_hi}, {wx, y_hi}));
  const Lattice cells = grow_lattice(rng, nx, ny, fill);
  int filled = 0;
  for (int ix = 0; ix < nx; ++ix)
    for (int iy = 0; iy < ny; ++iy) {
      if (!cells[ix][iy]) continue;
      ++filled;
      const Eigen::Vector2d c((ix + 0.5) * kCell_m, (iy + 0.5) * kCell_m);
      const std::string name = "cell_" + std::to_string(ix) + "_" + std::to_string(iy);
      if (rng.bernoulli(0.7)) {
        w.statics.push_back(pillar(name, c, rng.uniform(0.05, 0.075), kWallHeight_m));
      } else {
        const double side = rng.uniform(0.15, 0.25), height = rng.uniform(0.3, 0.8);
        w.statics.push_back(floor_box(name, c, 0.0, Eigen::Vector3d(side, side, height)));
      }
    }
  d.fill_ratio = static_cast<double>(filled) / (nx * ny);
  d.start = Pose2{rng.uniform(1.0, wx - 1.0), -1.5, 0.5 * std::numbers::pi};
  d.goal = Pose2{rng.uniform(1.0, wx - 1.0), field_y + 1.8, 0.5 * std::numbers::pi};
  d.way = {d.start.position(), d.goal.position()};
  return d;
}

}  // namespace bipednav::sim
