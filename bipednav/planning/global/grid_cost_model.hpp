#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "bipednav/mapping/costmap2d.hpp"

namespace bipednav::planning {

inline constexpr double kInfCost = std::numeric_limits<double>::infinity();

// How costmap values become edge costs of the 8-connected planning graph (section 5.1).
struct GridCostParams {
  double cost_weight = 3.0;          // w in factor = 1 + w * cost / 252
  bool unknown_is_obstacle = false;  // false: unknown cells are traversable (free-space assumption)
  int unknown_cost = 0;              // cost value used for a traversable unknown cell, in [0, 252]

  void validate() const;
};

// Traversal factor of one cell value: 1 + w * cost / 252, +inf when the robot's centre may not
// enter it (inscribed, lethal, and unknown when configured so). Pure kernel.
double cell_factor(std::uint8_t cost, const GridCostParams& p);

// Neighbour k of the 8-connected grid: 0..3 orthogonal (E, N, W, S), 4..7 diagonal.
inline constexpr std::array<int, 8> kDx = {1, 0, -1, 0, 1, -1, -1, 1};
inline constexpr std::array<int, 8> kDy = {0, 1, 0, -1, 1, 1, -1, -1};
inline constexpr int kNumNeighbours = 8;

// Octile distance in cells (|dx|, |dy| moves with diagonals of length sqrt 2).
inline double octile_cells(int dx, int dy) {
  const int ax = dx < 0 ? -dx : dx, ay = dy < 0 ? -dy : dy;
  const int mn = ax < ay ? ax : ay, mx = ax < ay ? ay : ax;
  return (mx - mn) + std::sqrt(2.0) * mn;
}

// The planner's own snapshot of the costmap with the edge cost model. A move from a to a
// neighbour b costs its length (m) times the mean of the two cells' factors, so costs are
// symmetric (Pred = Succ). A diagonal move needs both side cells traversable (no corner cutting).
// One cell (the robot's start) may be exempted from being impassable so the search can leave it.
class GridCostModel {
 public:
  explicit GridCostModel(const GridCostParams& params = {});

  // Copies a costmap's values and geometry; clears the exemption.
  void assign(const mapping::Costmap2D& map);
  void set_cost(std::size_t i, std::uint8_t c) { cost_[i] = c; }
  std::uint8_t cost(std::size_t i) const { return cost_[i]; }
  const std::vector<std::uint8_t>& costs() const { return cost_; }

  // The cell treated as traversable even if inscribed/unknown (-1: none), with its factor.
  void set_exempt(std::int64_t cell);
  std::int64_t exempt() const { return exempt_; }

  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t size() const { return cost_.size(); }
  double resolution_m() const { return resolution_m_; }
  const GridCostParams& params() const { return params_; }

  double factor(std::size_t i) const {
    return static_cast<std::int64_t>(i) == exempt_ ? exempt_factor_ : lut_[cost_[i]];
  }
  bool passable(std::size_t i) const { return std::isfinite(factor(i)); }

  // Cost of the move from cell (x, y) to its neighbour k; +inf if off the grid or blocked.
  double edge_cost(int x, int y, int k) const {
    const int nx = x + kDx[k], ny = y + kDy[k];
    if (nx < 0 || ny < 0 || nx >= width_ || ny >= height_) return kInfCost;
    const std::size_t a = idx(x, y), b = idx(nx, ny);
    const double f = 0.5 * (factor(a) + factor(b));
    if (k >= 4 && (!passable(idx(nx, y)) || !passable(idx(x, ny)))) return kInfCost;
    return f * step_len_[k];
  }
  // Admissible, consistent heuristic: octile length times the smallest possible factor (1).
  double heuristic(std::size_t a, std::size_t b) const {
    const int ax = static_cast<int>(a % width_), ay = static_cast<int>(a / width_);
    const int bx = static_cast<int>(b % width_), by = static_cast<int>(b / width_);
    return octile_cells(ax - bx, ay - by) * resolution_m_ * min_factor_;
  }
  std::size_t idx(int x, int y) const { return static_cast<std::size_t>(y) * width_ + x; }
  int x_of(std::size_t i) const { return static_cast<int>(i % width_); }
  int y_of(std::size_t i) const { return static_cast<int>(i / width_); }

 private:
  GridCostParams params_;
  std::array<double, 256> lut_{};
  std::array<double, 8> step_len_{};
  double min_factor_ = 1.0;
  double exempt_factor_ = 1.0;
  std::int64_t exempt_ = -1;
  int width_ = 0;
  int height_ = 0;
  double resolution_m_ = 1.0;
  std::vector<std::uint8_t> cost_;
};

}  // namespace bipednav::planning
