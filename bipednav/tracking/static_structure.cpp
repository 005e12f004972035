#include "bipednav/tracking/static_structure.hpp"

#include <cmath>
#include <limits>

namespace bipednav::tracking {

namespace {

constexpr double kNotLethal = std::numeric_limits<double>::infinity();

}  // namespace

void StaticStructure::update(const mapping::Costmap2D& occupancy, double stamp_s, double max_gap_s) {
  if (!std::isfinite(stamp_s) || stamp_s <= stamp_s_) return;
  const mapping::GridGeometry& g = occupancy.geometry();
  if (since_.size() != g.size() || g != geometry_) {
    geometry_ = g;
    since_.assign(g.size(), kNotLethal);
    last_.assign(g.size(), -kNotLethal);
    free_since_.assign(g.size(), kNotLethal);
    free_last_.assign(g.size(), -kNotLethal);
  }
  const auto& cost = occupancy.data();
  for (std::size_t i = 0; i < since_.size(); ++i) {
    if (cost[i] != mapping::kFree) continue;
    if (free_last_[i] != stamp_s_) free_since_[i] = stamp_s;
    free_last_[i] = stamp_s;
  }
  if (max_gap_s > 0.0) {
    for (std::size_t i = 0; i < since_.size(); ++i) {
      if (cost[i] == mapping::kLethal) {
        if (since_[i] == kNotLethal) since_[i] = stamp_s;
        last_[i] = stamp_s;
      } else if (stamp_s - last_[i] > max_gap_s) {
        since_[i] = kNotLethal;
      }
    }
  } else {
    for (std::size_t i = 0; i < since_.size(); ++i) {
      if (cost[i] != mapping::kLethal)
        since_[i] = kNotLethal;
      else if (since_[i] == kNotLethal)
        since_[i] = stamp_s;
    }
  }
  stamp_s_ = stamp_s;
}

void StaticStructure::clear() {
  since_.clear();
  last_.clear();
  free_since_.clear();
  free_last_.clear();
  geometry_ = {};
  stamp_s_ = -1e300;
}

bool StaticStructure::near(const Eigen::Vector2d& p, double margin_m, double min_age_s) const {
  if (since_.empty() || !p.allFinite()) return false;
  const auto c = geometry_.world_to_cell_unbounded(p.x(), p.y());
  if (!c) return false;
  const int k = static_cast<int>(std::ceil(margin_m / geometry_.resolution_m - 1e-9));
  const double latest = stamp_s_ - min_age_s;
  for (int dy = -k; dy <= k; ++dy) {
    for (int dx = -k; dx <= k; ++dx) {
      const int x = c->x + dx, y = c->y + dy;
      if (geometry_.in_bounds(x, y) && since_[geometry_.index(x, y)] <= latest) return true;
    }
  }
  return false;
}

bool StaticStructure::was_free(const Eigen::Vector2d& p, double min_span_s, double within_s) const {
  if (since_.empty() || !p.allFinite()) return false;
  const auto c = geometry_.world_to_cell(p.x(), p.y());
  if (!c) return false;
  const std::size_t i = geometry_.index(c->x, c->y);
  return free_last_[i] >= stamp_s_ - within_s && free_last_[i] - free_since_[i] >= min_span_s;
}

}  // namespace bipednav::tracking
