// Navigator::track_moving_obstacles: the moving-obstacle tracker fed with the local map's marking
// points, and the points on movers kept out of the maps' static marks.
#include <algorithm>
#include <cmath>
#include <limits>

#include "bipednav/navigation/navigator.hpp"

namespace bipednav::navigation {

namespace {

// The points of the marking observations as 2D points and their heights (the map's z: above the
// floor), in observation order.
void marking_points(const std::vector<mapping::Observation>& obs, std::vector<Eigen::Vector2d>& pts,
                    std::vector<double>& heights) {
  pts.clear();
  heights.clear();
  std::size_t total = 0;
  for (const auto& o : obs)
    if (o.marking) total += o.points_map.size();
  pts.resize(total);
  heights.resize(total);
  std::size_t filled = 0;
  for (const auto& o : obs) {
    if (!o.marking) continue;
    for (const auto& p : o.points_map) pts[filled] = Eigen::Vector2d(p.x(), p.y()), heights[filled++] = p.z();
  }
}

// Whether a point lies on a mover: within its radius plus `margin_m` of its position.
// (q - position).norm() <= r for a mover; most points are far from every mover, and their squared
// distance decides without the square root: sqrt rounds correctly, so a squared distance a
// millionth beyond r^2 (or within it) has a norm beyond (within) r. Near the circle (or when r is
// not a positive finite radius) the norm decides, as it always did.
class MoverCircles {
 public:
  MoverCircles(const std::vector<planning::local::TrackedObstacle>& moving, double margin_m) {
    for (const auto& m : moving) {
      const double r = m.radius_m + margin_m;
      const bool plain = std::isfinite(r) && r > 1e-100 && r < 1e100;
      constexpr double inf = std::numeric_limits<double>::infinity();
      circles_.push_back({m.position, r, plain ? r * r * (1.0 - 1e-6) : -inf, plain ? r * r * (1.0 + 1e-6) : inf});
    }
  }

  bool contain(const Eigen::Vector3f& p) const {
    const Eigen::Vector2d q(p.x(), p.y());
    for (const auto& c : circles_) {
      const Eigen::Vector2d v = q - c.position;
      const double s = v.squaredNorm();
      if (s > c.outside_sq) continue;
      if (s < c.inside_sq || v.norm() <= c.r) return true;
    }
    return false;
  }

 private:
  struct Circle {
    Eigen::Vector2d position;
    double r, inside_sq, outside_sq;
  };
  std::vector<Circle> circles_;
};

// Moves the points on movers of each marking observation of `obs` into an observation of their own
// that keeps no heights, appended to `obs` (its point buffer taken from `spare` when there is one).
void split_off_mover_points(std::vector<mapping::Observation>& obs, const MoverCircles& movers,
                            std::vector<std::vector<Eigen::Vector3f>>& spare) {
  const auto on_mover = [&](const Eigen::Vector3f& p) { return movers.contain(p); };
  const std::size_t n = obs.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (!obs[i].marking) continue;
    auto& pts = obs[i].points_map;
    // The points before the first one on a mover stay where they are: only the rest is partitioned
    // (no buffer for the stable partition of an observation without points on movers).
    const auto first_on = std::find_if(pts.begin(), pts.end(), on_mover);
    if (first_on == pts.end()) continue;
    const auto split = std::stable_partition(first_on, pts.end(), [&](const auto& p) { return !on_mover(p); });
    if (split == pts.end()) continue;
    mapping::Observation mover;
    mover.origin_map = obs[i].origin_map;
    mover.max_range_m = obs[i].max_range_m;
    mover.keep_heights = false;
    if (!spare.empty()) {
      mover.points_map = std::move(spare.back());
      spare.pop_back();
      mover.points_map.clear();
    }
    mover.points_map.insert(mover.points_map.end(), split, pts.end());
    pts.erase(split, pts.end());
    obs.push_back(std::move(mover));
  }
}

}  // namespace

void Navigator::track_moving_obstacles() {
  if (!params_.moving_obstacles.enabled) return;  // switched off: no point copies on the loop's hot path
  // The obstacle points of every sensor since the last local map update, in the map frame.
  marking_points(local_obs_, moving_points_, moving_heights_);
  moving_points_stamp_s_ = now_s_;
  if (moving_points_.empty()) return;
  moving_.update(moving_points_, moving_heights_, localizer_.T_map_base(), now_s_);
  // Points on moving obstacles stay out of the global map's own LiDAR input (their trail would
  // block the lanes they crossed); the local map marks them, and merge_local carries the local
  // map's cells into the global map, so the global planner routes round a mover where it is seen.
  const auto moving = moving_.moving(now_s_);
  if (moving.empty()) return;
  const MoverCircles movers(moving, params_.moving_obstacles.global_map_margin_m);
  const auto on_mover = [&](const Eigen::Vector3f& p) { return movers.contain(p); };
  for (auto& o : lidar_obs_) std::erase_if(o.points_map, on_mover);
  // In a height-aware local map a mover's cells keep no heights, so rays at any height clear them
  // once it has gone (a person seen at leg height by a depth camera, crossed higher up by the LiDAR).
  if (!params_.local_map.height_aware_clearing) return;
  split_off_mover_points(local_obs_, movers, spare_points_);
}

}  // namespace bipednav::navigation
