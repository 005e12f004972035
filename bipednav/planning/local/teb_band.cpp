#include "bipednav/planning/local/teb_band.hpp"

#include <algorithm>
#include <cmath>

#include "bipednav/common/angles.hpp"

namespace bipednav::planning::local {

double TebBand::duration_s() const {
  double t = 0.0;
  for (double dt : dt_s) t += dt;
  return t;
}

Path TebBand::to_path(const std::string& frame_id) const {
  Path p;
  p.frame_id = frame_id;
  p.poses = poses;
  double t = 0.0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    p.times_s.push_back(t);
    if (i < dt_s.size()) t += dt_s[i];
  }
  return p;
}

TebBand init_band(const Pose2& start, const std::vector<Eigen::Vector2d>& via, const Pose2& goal,
                  const TebLimits& limits, const TebBandParams& params) {
  std::vector<Eigen::Vector2d> pts{start.position()};
  for (const auto& v : via) {
    if ((v - pts.back()).norm() > 1e-3) pts.push_back(v);
  }
  if ((goal.position() - pts.back()).norm() > 1e-3 || pts.size() == 1) pts.push_back(goal.position());
  double total = 0.0;
  for (std::size_t i = 1; i < pts.size(); ++i) total += (pts[i] - pts[i - 1]).norm();
  const double step_ref = limits.velocity.max_vel_x_mps * params.dt_ref_s;
  int n_int = std::max(params.min_samples - 1, static_cast<int>(std::ceil(total / step_ref)));
  n_int = std::min(n_int, params.max_samples - 1);
  const double step = total / n_int;

  TebBand band;
  band.poses.push_back(start);
  std::size_t seg = 1;
  double seg_start = 0.0;  // arc length at pts[seg - 1]
  for (int k = 1; k < n_int; ++k) {
    const double s = k * step;
    while (seg + 1 < pts.size() && seg_start + (pts[seg] - pts[seg - 1]).norm() < s) {
      seg_start += (pts[seg] - pts[seg - 1]).norm();
      ++seg;
    }
    const Eigen::Vector2d d = pts[seg] - pts[seg - 1];
    const double len = d.norm();
    const double f = len > 1e-9 ? std::clamp((s - seg_start) / len, 0.0, 1.0) : 0.0;
    const Eigen::Vector2d p = pts[seg - 1] + f * d;
    const double th = len > 1e-9 ? std::atan2(d.y(), d.x()) : start.theta;
    band.poses.push_back({p.x(), p.y(), th});
  }
  band.poses.push_back(goal);
  const double dt = std::max(params.dt_min_s, step / limits.velocity.max_vel_x_mps);
  band.dt_s.assign(band.poses.size() - 1, dt);
  // Rotation in place (zero length) still needs time to turn.
  if (total < 1e-3) {
    const double turn = std::abs(angle_diff(goal.theta, start.theta)) / limits.velocity.max_vel_theta_radps;
    band.dt_s.assign(band.poses.size() - 1, std::max(params.dt_min_s, turn / static_cast<double>(n_int)));
    for (std::size_t k = 1; k + 1 < band.poses.size(); ++k) {
      const double f = static_cast<double>(k) / n_int;
      band.poses[k].theta = normalize_angle(start.theta + f * angle_diff(goal.theta, start.theta));
    }
  }
  return band;
}

namespace {

Pose2 midpoint(const Pose2& a, const Pose2& b) {
  return {0.5 * (a.x + b.x), 0.5 * (a.y + b.y), normalize_angle(a.theta + 0.5 * angle_diff(b.theta, a.theta))};
}

}  // namespace

bool resample_band(TebBand& band, const TebBandParams& params) {
  bool changed = false;
  // Repeated passes until stable; dt_hysteresis >= dt_ref / 3 (validated) guarantees that a split
  // interval is never merged again and a merged one never split again, so the count cannot oscillate.
  for (int pass = 0; pass < 100; ++pass) {
    bool pass_changed = false;
    for (std::size_t k = 0; k < band.dt_s.size(); ++k) {
      const int n = static_cast<int>(band.poses.size());
      if (band.dt_s[k] > params.dt_ref_s + params.dt_hysteresis_s && n < params.max_samples) {
        const double half = 0.5 * band.dt_s[k];
        band.poses.insert(band.poses.begin() + static_cast<long>(k) + 1, midpoint(band.poses[k], band.poses[k + 1]));
        band.dt_s[k] = half;
        band.dt_s.insert(band.dt_s.begin() + static_cast<long>(k) + 1, half);
        ++k;
        pass_changed = true;
      } else if (band.dt_s[k] < params.dt_ref_s - params.dt_hysteresis_s && n > params.min_samples &&
                 k + 1 < band.dt_s.size()) {
        band.dt_s[k] += band.dt_s[k + 1];  // remove pose k+1, merging its two intervals
        band.dt_s.erase(band.dt_s.begin() + static_cast<long>(k) + 1);
        band.poses.erase(band.poses.begin() + static_cast<long>(k) + 1);
        pass_changed = true;
      }
    }
    changed = changed || pass_changed;
    if (!pass_changed) break;
  }
  return changed;
}

bool warm_start_band(TebBand& band, const Pose2& start, const Pose2& goal, const TebBandParams& params) {
  if (band.size() < 2) return false;
  const Pose2& old_goal = band.poses.back();
  if (distance(old_goal, goal) > params.reinit_goal_dist_m ||
      std::abs(angle_diff(old_goal.theta, goal.theta)) > params.reinit_goal_angle_rad)
    return false;
  // Prune the poses the robot has passed: the nearest of the leading poses becomes the new start.
  std::size_t nearest = 0;
  double best = distance(band.poses[0], start);
  const std::size_t look = std::min<std::size_t>(band.size() - 1, 10);
  for (std::size_t k = 1; k < look; ++k) {
    const double d = distance(band.poses[k], start);
    if (d < best) best = d, nearest = k;
  }
  const std::size_t keep_min = static_cast<std::size_t>(params.min_samples);
  while (nearest > 0 && band.size() > keep_min) {
    band.poses.erase(band.poses.begin());
    band.dt_s.erase(band.dt_s.begin());
    --nearest;
  }
  band.poses.front() = start;
  band.poses.back() = goal;
  return true;
}

}  // namespace bipednav::planning::local
