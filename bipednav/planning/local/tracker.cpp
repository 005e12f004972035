#include "bipednav/planning/local/tracker.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "bipednav/common/angles.hpp"
#include "bipednav/common/error.hpp"

namespace bipednav::planning::local {

void TrackerParams::validate() const {
  const auto pos = [](double v) { return std::isfinite(v) && v > 0.0; };
  require(pos(lookahead_m), "lookahead_m", "> 0");
  limits.validate();
  require(pos(rotate_in_place_angle_rad), "rotate_in_place_angle_rad", "> 0");
  require(pos(xy_goal_tolerance_m), "xy_goal_tolerance_m", "> 0");
  require(pos(yaw_goal_tolerance_rad), "yaw_goal_tolerance_rad", "> 0");
  require(std::isfinite(xy_goal_release_m) && xy_goal_release_m >= 0.0, "xy_goal_release_m", ">= 0");
  require(pos(rotate_gain), "rotate_gain", "> 0");
  require(pos(control_period_s), "control_period_s", "> 0");
  require(pos(collision_check_horizon_s), "collision_check_horizon_s", "> 0");
}

Twist pure_pursuit_command(const Eigen::Vector2d& target_in_base, double dist_to_goal_m, const TrackerParams& p) {
  Twist t;
  const double alpha = std::atan2(target_in_base.y(), target_in_base.x());
  if (std::abs(alpha) > p.rotate_in_place_angle_rad) {
    t.angular_z = std::clamp(p.rotate_gain * alpha, -p.limits.max_vel_theta_radps, p.limits.max_vel_theta_radps);
    return t;
  }
  const double l2 = std::max(target_in_base.squaredNorm(), 1e-6);
  const double kappa = 2.0 * target_in_base.y() / l2;
  double v = std::min(p.limits.max_vel_x_mps, std::max(0.05, dist_to_goal_m));  // slow down on the last metre
  if (std::abs(kappa * v) > p.limits.max_vel_theta_radps) v = p.limits.max_vel_theta_radps / std::abs(kappa);
  t.linear_x = v;
  t.angular_z = kappa * v;
  return t;
}

namespace {

constexpr double kLargeScore = 1e300;

// The poses of the robot holding `cmd` for horizon_s, every 0.05 s from `start`.
Path simulate_arc(const Pose2& start, const Twist& cmd, double horizon_s, const std::string& frame_id) {
  Path arc;
  arc.frame_id = frame_id;
  Pose2 p = start;
  const double dt = 0.05;
  for (double t = 0.0; t <= horizon_s + 1e-9; t += dt) {
    arc.poses.push_back(p);
    arc.times_s.push_back(t);
    p = p * Pose2{cmd.linear_x * dt, 0.0, cmd.angular_z * dt};
  }
  return arc;
}

}  // namespace

PathTracker::PathTracker(TrackerParams params) : params_(std::move(params)) { params_.validate(); }

LocalPlanResult PathTracker::compute(const Pose2& T_map_base, const Twist& current_velocity, const Path& global_plan,
                                     const mapping::Costmap2D& local_costmap, double now_s) {
  LocalPlanResult r = follow(T_map_base, current_velocity, global_plan, local_costmap);
  const VelocityLimits lim = params_.limits;
  yield(r, T_map_base, current_velocity, local_costmap, lim, params_.control_period_s, now_s);
  return r;
}

LocalPlanResult PathTracker::follow(const Pose2& T_map_base, const Twist& current_velocity, const Path& global_plan,
                                    const mapping::Costmap2D& local_costmap) {
  if (auto bad = reject_bad_inputs(T_map_base, current_velocity, global_plan, local_costmap)) return *bad;
  LocalPlanResult r;
  r.trajectory.frame_id = global_plan.frame_id;
  VelocityLimits lim = params_.limits;
  lim.max_vel_x_backwards_mps = 0.0;
  const Pose2& goal = global_plan.poses.back();
  const GoalApproach ga =
      approach_goal(T_map_base, goal, xy_goal_tolerance(params_.xy_goal_tolerance_m), params_.yaw_goal_tolerance_rad,
                    params_.rotate_gain, params_.limits.max_vel_theta_radps, params_.xy_goal_release_m, &holding_goal_);
  Twist desired = ga.cmd;
  r.goal_reached = ga.reached;
  if (!ga.near) {
    // Lookahead point: the first plan pose after the nearest one that is lookahead_m away.
    const LocalGoal lg = select_local_goal(global_plan, T_map_base, local_costmap, params_.lookahead_m, 0.0, 1e9);
    const Eigen::Vector2d target = T_map_base.inverse().transform(lg.goal.position());
    desired = pure_pursuit_command(target, distance(T_map_base, goal), params_);
  }
  r.cmd = limit_velocity(desired, current_velocity, params_.control_period_s, lim);
  // Forward-simulate the arc for display and the collision check.
  r.trajectory = simulate_arc(T_map_base, r.cmd, params_.collision_check_horizon_s, global_plan.frame_id);
  if (!poses_keep_clearance(r.trajectory.poses, local_costmap)) {
    if (escape(r, T_map_base, current_velocity, desired, local_costmap)) return r;
    r.result = {Outcome::BLOCKED_PATH, "the tracked arc enters lethal or inscribed cells"};
    r.cmd = Twist{};
    return r;
  }
  r.result.message = ga.reached ? "goal reached" : "ok";
  return r;
}

bool PathTracker::escape(LocalPlanResult& r, const Pose2& T_map_base, const Twist& current_velocity,
                         const Twist& desired, const mapping::Costmap2D& local_costmap) const {
  const auto& g = local_costmap.geometry();
  const auto cell = g.world_to_cell(T_map_base.x, T_map_base.y);
  if (!cell) return false;
  const int own = local_costmap.cost(*cell);
  if (own < mapping::kInscribed || own == mapping::kUnknown) return false;
  constexpr double kSearchM = 3.0;
  Eigen::Vector2d nearest;
  const double start = lethal_clearance(local_costmap, T_map_base.x, T_map_base.y, kSearchM, &nearest);
  if (!std::isfinite(start)) return false;
  // Away from the nearest lethal cell (any direction when the robot sits on its centre).
  const Eigen::Vector2d away = T_map_base.position() - nearest;
  const double away_yaw = away.norm() > 1e-9 ? std::atan2(away.y(), away.x()) : T_map_base.theta;
  const VelocityLimits lim = params_.limits;
  const double vb = params_.limits.max_vel_x_backwards_mps, vf = params_.limits.max_vel_x_mps,
               wm = params_.limits.max_vel_theta_radps;
  // Candidates: a grid of backing, turning and forward commands within one period's acceleration.
  // Score: the clearance gained at the end of the arc, then (to pick a turn on the spot) how
  // squarely the robot ends up facing away, then closeness to the tracker's command.
  bool found = false;
  double best_score = -kLargeScore;
  Twist best_cmd;
  Path best_arc;
  for (const double v : {-vb, -0.5 * vb, 0.0, 0.5 * vf, vf}) {
    for (const double w : {-wm, -0.5 * wm, 0.0, 0.5 * wm, wm}) {
      const Twist c = limit_velocity({v, 0.0, w}, current_velocity, params_.control_period_s, lim);
      Path arc = simulate_arc(T_map_base, c, params_.collision_check_horizon_s, r.trajectory.frame_id);
      if (!poses_keep_clearance(arc.poses, local_costmap)) continue;
      const Pose2& end = arc.poses.back();
      const double gain = std::min(lethal_clearance(local_costmap, end.x, end.y, kSearchM), start + 1.0) - start;
      const double facing = std::cos(angle_diff(away_yaw, end.theta));
      const double deviation = std::abs(c.linear_x - desired.linear_x) / std::max(vf, 1e-3) +
                               std::abs(c.angular_z - desired.angular_z) / std::max(wm, 1e-3);
      const double score = gain + 0.05 * facing - 1e-3 * deviation;
      if (!found || score > best_score) found = true, best_score = score, best_cmd = c, best_arc = std::move(arc);
    }
  }
  if (!found) return false;
  r.cmd = best_cmd;
  r.trajectory = std::move(best_arc);
  r.goal_reached = false;
  r.result = {Outcome::SUCCESS, "leaving inscribed space"};
  return true;
}

}  // namespace bipednav::planning::local
