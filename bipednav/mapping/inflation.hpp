#pragma once

#include <cstdint>
#include <vector>

#include "bipednav/mapping/cell_rect.hpp"
#include "bipednav/mapping/costmap2d.hpp"

namespace bipednav::mapping {

// Inflation around lethal cells (ROS costmap_2d / Nav2 inflation layer).
struct InflationParams {
  double inscribed_radius_m = 0.2;   // robot footprint's inscribed radius
  double inflation_radius_m = 0.55;  // costs fall to 0 beyond this distance from an obstacle
  double cost_scaling_factor = 3.0;  // 1/m, decay rate of the exponential

  void validate() const;
};

// Cost of a cell whose centre is `distance_m` from the centre of the nearest lethal cell:
// 254 at 0, 253 up to the inscribed radius, 252 * exp(-k (d - r_inscribed)) (truncated) up to the
// inflation radius, 0 beyond (the Nav2 formula).
std::uint8_t inflation_cost(double distance_m, const InflationParams& p);

// Computes inflated costs with an exact Euclidean distance transform bounded by the inflation
// radius R (in cells): a column pass gives the vertical distance to the nearest lethal cell
// (capped at R+1), a row pass takes min over |dx| <= R of dx^2 + g(x+dx)^2 — exact for every
// distance <= R — and a lookup table turns squared cell distances into costs.
class Inflator {
 public:
  Inflator(const InflationParams& params, double resolution_m);

  // out(c) = inflation cost of c given the lethal cells (== kLethal) of `obstacles`, for every cell
  // c of `region` (clipped to the grid); cells of `out` outside the region are left untouched.
  // `out` must have the geometry of `obstacles` (it is resized and re-origined when it has not).
  void inflate(const Costmap2D& obstacles, Costmap2D& out, CellRect region);
  void inflate(const Costmap2D& obstacles, Costmap2D& out) {
    inflate(obstacles, out, CellRect::all(obstacles.geometry()));
  }

  // Cells beyond which costs are zero: a change of an obstacle affects at most this far.
  int radius_cells() const { return radius_cells_; }
  const InflationParams& params() const { return params_; }
  double resolution_m() const { return resolution_m_; }

 private:
  InflationParams params_;
  double resolution_m_;
  int radius_cells_;
  std::vector<std::uint8_t> cost_of_d2_;  // cost by squared distance in cells
  std::vector<std::int16_t> g2_;          // scratch: squared column distances, padded window
  std::vector<std::int16_t> row_;         // scratch: one row of squared distances
};

}  // namespace bipednav::mapping
