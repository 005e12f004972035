#include "bipednav/planning/local/plan_utils.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bipednav/common/angles.hpp"

namespace bipednav::planning::local {

std::optional<Result> check_inputs(const Pose2& T_map_base, const Twist& velocity, const Path& plan,
                                   const mapping::Costmap2D& costmap) {
  if (!T_map_base.is_finite()) return Result{Outcome::CTRL_TF_ERROR, "robot pose is not finite"};
  if (!velocity.is_finite()) return Result{Outcome::CTRL_TF_ERROR, "current velocity is not finite"};
  if (plan.empty()) return Result{Outcome::INVALID_PATH, "global plan is empty"};
  for (const auto& p : plan.poses) {
    if (!p.is_finite()) return Result{Outcome::INVALID_PATH, "global plan contains a non-finite pose"};
  }
  if (costmap.width() <= 0 || costmap.height() <= 0 || costmap.data().size() != costmap.geometry().size())
    return Result{Outcome::CTRL_MAP_ERROR, "local costmap is empty"};
  if (!costmap.geometry().world_to_cell(T_map_base.x, T_map_base.y))
    return Result{Outcome::CTRL_OUT_OF_MAP, "robot is outside the local costmap"};
  return std::nullopt;
}

namespace {

// Named apart from moving_obstacles.cpp's kInf: the sanitizer build compiles this library as unity batches.
constexpr double kNoClearance = std::numeric_limits<double>::infinity();

bool inside_window(const mapping::GridGeometry& g, const Pose2& p, double margin) {
  return p.x >= g.origin_x_m + margin && p.y >= g.origin_y_m + margin && p.x <= g.origin_x_m + g.size_x_m() - margin &&
         p.y <= g.origin_y_m + g.size_y_m() - margin;
}

// The cost of the cell under (x, y); -1 off the map.
int cost_at_point(const mapping::Costmap2D& costmap, double x, double y) {
  const auto c = costmap.geometry().world_to_cell(x, y);
  return c ? costmap.cost(*c) : -1;
}

// Whether bad(x, y) holds at any point sampled along the poses' segments, one sample per cell
// length (the first pose itself is not sampled).
template <typename Pred>
bool any_sampled_point(const std::vector<Pose2>& poses, double step_m, const Pred& bad) {
  for (std::size_t i = 1; i < poses.size(); ++i) {
    const double len = distance(poses[i - 1], poses[i]);
    const int steps = std::max(1, static_cast<int>(std::ceil(len / step_m)));
    for (int s = 1; s <= steps; ++s) {
      const double f = static_cast<double>(s) / steps;
      if (bad(poses[i - 1].x + f * (poses[i].x - poses[i - 1].x), poses[i - 1].y + f * (poses[i].y - poses[i - 1].y)))
        return true;
    }
  }
  return false;
}

}  // namespace

LocalGoal select_local_goal(const Path& plan, const Pose2& T_map_base, const mapping::Costmap2D& costmap,
                            double lookahead_m, double margin_m, double via_sep_m) {
  const auto& g = costmap.geometry();
  const auto& P = plan.poses;
  // Nearest plan pose, searched until the plan first leaves the window after having been inside.
  std::size_t nearest = 0;
  double best = 1e300;
  bool was_inside = false;
  for (std::size_t i = 0; i < P.size(); ++i) {
    const bool in = inside_window(g, P[i], 0.0);
    if (was_inside && !in) break;
    was_inside = was_inside || in;
    const double d = distance(P[i], T_map_base);
    if (d < best) best = d, nearest = i;
  }
  LocalGoal lg;
  std::size_t goal_idx = nearest;
  double arc = 0.0, since_via = 0.0;
  for (std::size_t i = nearest + 1; i < P.size(); ++i) {
    const double step = distance(P[i - 1], P[i]);
    if (!inside_window(g, P[i], margin_m) || arc + step > lookahead_m) break;
    arc += step, since_via += step;
    goal_idx = i;
    if (since_via >= via_sep_m) lg.via_points.push_back(P[i].position()), since_via = 0.0;
  }
  lg.is_final = goal_idx + 1 == P.size();
  lg.goal = P[goal_idx];
  if (!lg.is_final) {
    // Intermediate goals face along the path (global planners often leave theta at 0).
    const Pose2& a = P[goal_idx];
    const Pose2& b = P[goal_idx + 1];
    if (distance(a, b) > 1e-9) lg.goal.theta = std::atan2(b.y - a.y, b.x - a.x);
  }
  if (!lg.via_points.empty() && (lg.via_points.back() - lg.goal.position()).norm() < 0.5 * via_sep_m)
    lg.via_points.pop_back();
  return lg;
}

bool poses_feasible(const std::vector<Pose2>& poses, const mapping::Costmap2D& costmap) {
  if (poses.empty()) return true;
  const auto& g = costmap.geometry();
  const auto cost_at = [&](double x, double y) { return cost_at_point(costmap, x, y); };
  const int own = cost_at(poses.front().x, poses.front().y);
  const int limit = own >= mapping::kInscribed && own != mapping::kUnknown ? mapping::kLethal : mapping::kInscribed;
  const auto bad = [&](double x, double y) {
    const int c = cost_at(x, y);
    return c >= limit && c != mapping::kUnknown;
  };
  return !any_sampled_point(poses, g.resolution_m, bad);
}

double lethal_clearance(const mapping::Costmap2D& costmap, double x, double y, double max_m, Eigen::Vector2d* nearest) {
  const auto& g = costmap.geometry();
  const auto c = g.world_to_cell_unbounded(x, y);
  if (!c || !std::isfinite(max_m) || max_m < 0.0) return kNoClearance;
  const int rings = static_cast<int>(std::ceil(max_m / g.resolution_m)) + 1;
  double best2 = max_m * max_m;
  bool found = false;
  const auto visit = [&](int cx, int cy) {
    if (!g.in_bounds(cx, cy) || costmap.cost(cx, cy) != mapping::kLethal) return;
    const Eigen::Vector2d d = g.cell_center(cx, cy) - Eigen::Vector2d{x, y};
    if (d.squaredNorm() < best2 || (!found && d.squaredNorm() <= best2)) {
      best2 = d.squaredNorm(), found = true;
      if (nearest) *nearest = g.cell_center(cx, cy);
    }
  };
  for (int k = 0; k <= rings; ++k) {
    // Every cell centre on ring k (Chebyshev distance k from the point's cell) is at least
    // (k - 0.5) cells away from the point.
    const double lower = std::max(0.0, (k - 0.5) * g.resolution_m);
    if (lower * lower > best2) break;
    if (k == 0) {
      visit(c->x, c->y);
      continue;
    }
    for (int i = -k; i <= k; ++i) {
      visit(c->x + i, c->y - k);
      visit(c->x + i, c->y + k);
    }
    for (int i = -k + 1; i <= k - 1; ++i) {
      visit(c->x - k, c->y + i);
      visit(c->x + k, c->y + i);
    }
  }
  return found ? std::sqrt(best2) : kNoClearance;
}

bool poses_keep_clearance(const std::vector<Pose2>& poses, const mapping::Costmap2D& costmap) {
  if (poses.empty()) return true;
  const auto& g = costmap.geometry();
  const auto cost_at = [&](double x, double y) { return cost_at_point(costmap, x, y); };
  const int own = cost_at(poses.front().x, poses.front().y);
  if (own < mapping::kInscribed || own == mapping::kUnknown) return poses_feasible(poses, costmap);
  // Only points in inscribed or lethal cells are checked, and those lie within the inscribed
  // radius of a lethal cell: a search out to a few metres finds their nearest one.
  constexpr double kSearchM = 3.0;
  const double start = lethal_clearance(costmap, poses.front().x, poses.front().y, kSearchM);
  const auto bad = [&](double x, double y) {
    const int c = cost_at(x, y);
    if (c < mapping::kInscribed || c == mapping::kUnknown) return false;
    if (c == mapping::kLethal && own != mapping::kLethal) return true;
    return lethal_clearance(costmap, x, y, kSearchM) < start;
  };
  return !any_sampled_point(poses, g.resolution_m, bad);
}

GoalApproach approach_goal(const Pose2& T_map_base, const Pose2& goal, double xy_tol_m, double yaw_tol_rad,
                           double rotate_gain, double max_vel_theta_radps, double release_m, bool* holding) {
  GoalApproach a;
  const double d = distance(T_map_base, goal);
  a.near = d <= xy_tol_m || (holding != nullptr && *holding && d <= release_m);
  if (holding != nullptr) *holding = a.near;
  if (!a.near) return a;
  const double err = angle_diff(goal.theta, T_map_base.theta);
  a.reached = std::abs(err) <= yaw_tol_rad;
  if (!a.reached) a.cmd.angular_z = std::clamp(rotate_gain * err, -max_vel_theta_radps, max_vel_theta_radps);
  return a;
}

OscillationDetector::OscillationDetector(int window, double max_vel_x_mps, double max_vel_theta_radps)
    : window_(static_cast<std::size_t>(std::max(window, 4))), max_v_(max_vel_x_mps), max_w_(max_vel_theta_radps) {}

void OscillationDetector::update(const Twist& cmd) {
  history_.push_back(cmd);
  if (history_.size() > window_) history_.erase(history_.begin());
}

bool OscillationDetector::oscillating() const {
  if (history_.size() < window_) return false;
  double mv = 0.0, mw = 0.0, av = 0.0, aw = 0.0;
  int flips_v = 0, flips_w = 0, last_v = 0, last_w = 0;
  for (const auto& t : history_) {
    mv += t.linear_x, mw += t.angular_z, av += std::abs(t.linear_x), aw += std::abs(t.angular_z);
    const int sv = t.linear_x > 0.05 * max_v_ ? 1 : (t.linear_x < -0.05 * max_v_ ? -1 : 0);
    const int sw = t.angular_z > 0.05 * max_w_ ? 1 : (t.angular_z < -0.05 * max_w_ ? -1 : 0);
    if (sv != 0 && last_v != 0 && sv != last_v) ++flips_v;
    if (sw != 0 && last_w != 0 && sw != last_w) ++flips_w;
    if (sv != 0) last_v = sv;
    if (sw != 0) last_w = sw;
  }
  const double n = static_cast<double>(history_.size());
  mv /= n, mw /= n, av /= n, aw /= n;
  const bool small_mean = std::abs(mv) < 0.1 * max_v_ && std::abs(mw) < 0.1 * max_w_;
  const bool active = av > 0.1 * max_v_ || aw > 0.1 * max_w_;
  return small_mean && active && (flips_v >= 3 || flips_w >= 3);
}

// The distance from p to the segment [a, b].
double point_segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + s * ab)).norm();
}

}  // namespace bipednav::planning::local
