#include "bipednav/planning/global/grid_cost_model.hpp"

#include <algorithm>
#include <limits>

#include "bipednav/common/error.hpp"

namespace bipednav::planning::global {

void GridCostParams::validate() const {
  require(std::isfinite(cost_weight) && cost_weight >= 0.0 && cost_weight <= 50.0, "cost_weight", "a value in [0, 50]");
  require(unknown_cost >= 0 && unknown_cost <= 252, "unknown_cost", "a cost value in [0, 252]");
  require(min_impassable_cost >= 1 && min_impassable_cost <= mapping::kInscribed, "min_impassable_cost",
          "a cost value in [1, 253]");
}

double cell_factor(std::uint8_t cost, const GridCostParams& p) {
  if (cost == mapping::kUnknown) {
    if (p.unknown_is_obstacle) return std::numeric_limits<double>::infinity();
    cost = static_cast<std::uint8_t>(p.unknown_cost);
  } else if (cost >= p.min_impassable_cost) {
    return std::numeric_limits<double>::infinity();
  }
  if (cost >= mapping::kInscribed) return std::numeric_limits<double>::infinity();
  return 1.0 + p.cost_weight * static_cast<double>(cost) / 252.0;
}

int min_impassable_cost(double clearance_m, const mapping::InflationParams& p) {
  if (!(clearance_m > p.inscribed_radius_m)) return mapping::kInscribed;
  // A cell at exactly clearance_m stays open: one cost unit above the cost there closes the nearer
  // cells (a nearer cell the truncation gives the same cost stays open, within a few mm).
  const double d = std::min(clearance_m, p.inflation_radius_m);
  return std::min<int>(mapping::kInscribed, mapping::inflation_cost(d, p) + 1);
}

GridCostModel::GridCostModel(const GridCostParams& params) : params_(params) {
  params_.validate();
  for (int c = 0; c < 256; ++c) {
    const double f = cell_factor(static_cast<std::uint8_t>(c), params_);
    lut_[c] = std::isfinite(f) ? std::llround(f * kFactorUnit) : kInfCost;
  }
  // The cheapest factor any cell can have keeps the heuristic admissible.
  min_factor_ = *std::min_element(lut_.begin(), lut_.end());
  // An exempted start cell costs as much as the most expensive traversable cell.
  exempt_factor_ = std::llround((1.0 + params_.cost_weight) * kFactorUnit);
}

void GridCostModel::assign(const mapping::Costmap2D& map) {
  width_ = map.width();
  height_ = map.height();
  resolution_m_ = map.resolution_m();
  cost_ = map.data();
  exempt_ = -1;
}

}  // namespace bipednav::planning::global
