#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "bipednav/mapping/costmap2d.hpp"
#include "bipednav/mapping/inflation.hpp"

namespace bipednav::planning::global {

// Path costs are exact fixed-point integers: D* Lite's equality tests (Algorithm 3 line 28,
// Algorithm 4 line 20) and its key ties (eqs. 5.2-5.3) must not depend on rounding.
using Cost = std::int64_t;
inline constexpr Cost kInfCost = Cost{1} << 62;
inline constexpr Cost kLengthUnit = Cost{1} << 24;  // one cell edge
inline constexpr Cost kFactorUnit = 1024;           // factor 1.0
inline Cost add_cost(Cost a, Cost b) { return (a >= kInfCost || b >= kInfCost) ? kInfCost : a + b; }

// How costmap values become edge costs of the 8-connected planning graph (section 5.1).
struct GridCostParams {
  double cost_weight = 3.0;          // w in factor = 1 + w * cost / 252, in [0, 50]
  bool unknown_is_obstacle = false;  // false: unknown cells are traversable (free-space assumption)
  int unknown_cost = 0;              // cost value used for a traversable unknown cell, in [0, 252]
  // Mapped cells of this cost or more are impassable, in [1, 253]: kInscribed (253) lets the
  // robot's centre enter every cell outside the inscribed radius; a lower value keeps it farther
  // from obstacles (min_impassable_cost(); the navigation server sets it from the clearance it
  // plans with). Unknown cells keep unknown_is_obstacle / unknown_cost.
  int min_impassable_cost = mapping::kInscribed;

  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp). min_impassable_cost is left
  // out: the navigation server sets it (ServerParams::plan_clearance_sigmas).
  template <class V>
  void visit_fields(V& v) {
    v("cost_weight", cost_weight);
    v("unknown_is_obstacle", unknown_is_obstacle);
    v("unknown_cost", unknown_cost);
  }
};

// Traversal factor of one cell value: 1 + w * cost / 252, +inf when the robot's centre may not
// enter it (min_impassable_cost or more, lethal, and unknown when configured so). Pure kernel.
double cell_factor(std::uint8_t cost, const GridCostParams& p);

// The min_impassable_cost that closes every cell whose centre lies nearer than `clearance_m` to
// the centre of a lethal cell under the inflation `p` (inflation_cost is non-increasing in the
// distance): kInscribed for a clearance within the inscribed radius; beyond the inflation radius,
// whose cells all cost 0, one above the cost at the inflation radius (the cells nearer than it
// close). Pure kernel.
int min_impassable_cost(double clearance_m, const mapping::InflationParams& p);

// Neighbour k of the 8-connected grid: 0..3 orthogonal (E, N, W, S), 4..7 diagonal.
inline constexpr std::array<int, 8> kDx = {1, 0, -1, 0, 1, -1, -1, 1};
inline constexpr std::array<int, 8> kDy = {0, 1, 0, -1, 1, 1, -1, -1};
inline constexpr int kNumNeighbours = 8;

// The planner's own snapshot of the costmap with the edge cost model. A move from a to a
// neighbour b costs its length times the mean of the two cells' factors, so costs are symmetric
// (Pred = Succ). A diagonal move needs both side cells traversable (no corner cutting). One cell
// (the robot's start) may be exempted from being impassable so the search can leave it.
// Internally a cost is length / kLengthUnit cells times factor sum / (2 kFactorUnit).
class GridCostModel {
 public:
  explicit GridCostModel(const GridCostParams& params = {});

  // Copies a costmap's values and geometry; clears the exemption.
  void assign(const mapping::Costmap2D& map);
  void set_cost(std::size_t i, std::uint8_t c) { cost_[i] = c; }
  std::uint8_t cost(std::size_t i) const { return cost_[i]; }
  const std::vector<std::uint8_t>& costs() const { return cost_; }

  // The cell treated as traversable even if inscribed/unknown (-1: none).
  void set_exempt(std::int64_t cell) { exempt_ = cell; }
  std::int64_t exempt() const { return exempt_; }

  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t size() const { return cost_.size(); }
  double resolution_m() const { return resolution_m_; }
  const GridCostParams& params() const { return params_; }

  // Fixed-point factor of a cell (kInfCost when impassable).
  Cost factor(std::size_t i) const { return static_cast<std::int64_t>(i) == exempt_ ? exempt_factor_ : lut_[cost_[i]]; }
  bool passable(std::size_t i) const { return factor(i) < kInfCost; }

  // Cost of the move from cell (x, y) to its neighbour k; kInfCost if off the grid or blocked.
  Cost edge_cost(int x, int y, int k) const {
    const int nx = x + kDx[k], ny = y + kDy[k];
    if (nx < 0 || ny < 0 || nx >= width_ || ny >= height_) return kInfCost;
    const Cost fa = factor(idx(x, y)), fb = factor(idx(nx, ny));
    if (fa >= kInfCost || fb >= kInfCost) return kInfCost;
    if (k >= 4 && (!passable(idx(nx, y)) || !passable(idx(x, ny)))) return kInfCost;
    return kStepLen[k] * (fa + fb);
  }
  // Admissible, consistent heuristic: octile length times the smallest possible factor sum.
  Cost octile(int dx, int dy) const {
    dx = dx < 0 ? -dx : dx;
    dy = dy < 0 ? -dy : dy;
    const Cost mn = dx < dy ? dx : dy, mx = dx < dy ? dy : dx;
    return ((mx - mn) * kStepLen[0] + mn * kStepLen[4]) * 2 * min_factor_;
  }
  Cost heuristic(std::size_t a, std::size_t b) const { return octile(x_of(a) - x_of(b), y_of(a) - y_of(b)); }
  // A path cost in metres (times the factors): cells x resolution.
  double to_metres(Cost c) const { return static_cast<double>(c) / (2.0 * kFactorUnit * kLengthUnit) * resolution_m_; }

  std::size_t idx(int x, int y) const { return static_cast<std::size_t>(y) * width_ + x; }
  int x_of(std::size_t i) const { return static_cast<int>(i % width_); }
  int y_of(std::size_t i) const { return static_cast<int>(i / width_); }

  static constexpr Cost kDiagonalLen = 23726566;  // round(sqrt(2) * 2^24)
  static constexpr std::array<Cost, 8> kStepLen = {kLengthUnit,  kLengthUnit,  kLengthUnit,  kLengthUnit,
                                                   kDiagonalLen, kDiagonalLen, kDiagonalLen, kDiagonalLen};

 private:
  GridCostParams params_;
  std::array<Cost, 256> lut_{};
  Cost min_factor_ = kFactorUnit;
  Cost exempt_factor_ = kFactorUnit;
  std::int64_t exempt_ = -1;
  int width_ = 0;
  int height_ = 0;
  double resolution_m_ = 1.0;
  std::vector<std::uint8_t> cost_;
};

}  // namespace bipednav::planning::global
