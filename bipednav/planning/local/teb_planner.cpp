#include "bipednav/planning/local/teb_planner.hpp"

#include <algorithm>
#include <cmath>

#include "bipednav/common/angles.hpp"

namespace bipednav::planning::local {

Twist band_command(const TebBand& band) {
  Twist t;
  if (band.size() < 2 || band.dt_s.empty() || !(band.dt_s[0] > 0.0)) return t;
  const Pose2& a = band.poses[0];
  const Pose2& b = band.poses[1];
  t.linear_x = exact_linear_velocity(a.x, a.y, a.theta, b.x, b.y, band.dt_s[0]);
  t.angular_z = angle_diff(b.theta, a.theta) / band.dt_s[0];
  return t.is_finite() ? t : Twist{};
}

TebPlanner::TebPlanner(TebParams params)
    : params_((params.validate(), std::move(params))),
      homotopy_(params_),
      oscillation_(params_.oscillation_window, params_.limits.velocity.max_vel_x_mps,
                   params_.limits.velocity.max_vel_theta_radps) {}

void TebPlanner::reset() {
  homotopy_.reset();
  oscillation_.clear();
  obstacles_.clear();
  holding_goal_ = false;
  last_cmd_ = body_ = Twist{};
}

VelocityLimits TebPlanner::command_limits() const { return params_.limits.velocity; }

Twist TebPlanner::body_velocity(const Twist& given) {
  if (!models_lag()) return given;
  // Where the given velocity is the last command (a walker's braking reference passes the command
  // when it is nearer zero than the lagging measurement), the body still moves at the lag's
  // prediction from the previous cycle's velocity under that command. Only TEB's own command: when
  // the yield replaced it, predicting the body under the replacement lost on Digit's seeds 11-30
  // (66/80 against 75/80, cube contacts in three_rooms).
  const Twist predicted = predict_body_velocity(body_, last_cmd_, params_.control_period_s, body_lag());
  Twist b = given;
  if (given.linear_x == last_cmd_.linear_x && std::abs(predicted.linear_x) > std::abs(given.linear_x))
    b.linear_x = predicted.linear_x;
  if (given.angular_z == last_cmd_.angular_z && std::abs(predicted.angular_z) > std::abs(given.angular_z))
    b.angular_z = predicted.angular_z;
  body_ = b;
  return b;
}

LocalPlanResult TebPlanner::finish(LocalPlanResult r, const Twist& desired, const Twist& current) {
  r.cmd = limit_velocity(desired, current, params_.control_period_s, command_limits());
  if (!r.result.ok()) {
    r.cmd = Twist{};
    return r;
  }
  oscillation_.update(r.cmd);
  if (oscillation_.oscillating()) {
    oscillation_.clear();
    r.result = {Outcome::OSCILLATION, "the commands oscillate without progress"};
    r.cmd = Twist{};
  }
  return r;
}

LocalPlanResult TebPlanner::compute(const Pose2& T_map_base, const Twist& current_velocity, const Path& global_plan,
                                    const mapping::Costmap2D& local_costmap, double now_s) {
  LocalPlanResult r = plan(T_map_base, current_velocity, global_plan, local_costmap, now_s);
  const bool lag = models_lag();
  // With the lag model, the band's (or the yield's) velocity is the body's target for the next period:
  // reachable from the body's velocity within the acceleration limits, and the command sent is the one
  // that brings the lagging body there within the horizon (a lagging body needs a larger step). A failed
  // cycle's command stays zero.
  yield(r, T_map_base, lag ? body_ : current_velocity, local_costmap, command_limits(), params_.control_period_s,
        now_s);
  if (lag && r.result.ok()) {
    const double h = params_.response.horizon_s > 0.0 ? params_.response.horizon_s : params_.control_period_s;
    r.cmd = invert_body_lag(body_, r.cmd, h, body_lag());
  }
  last_cmd_ = r.cmd;
  return r;
}

std::vector<TebMovingObstacle> TebPlanner::band_moving(double now_s) const {
  std::vector<TebMovingObstacle> out;
  if (!params_.optim.dynamic_obstacles || !moving_ || !moving_->params().enabled || !std::isfinite(now_s)) return out;
  const auto& op = params_.optim;
  for (const auto& t : moving_->moving(now_s)) {
    TebMovingObstacle o;
    o.position = t.predict(now_s);
    o.velocity = t.velocity;
    o.radius_m = op.dynamic_obstacle_largest_radius ? std::max(t.radius_m, t.max_radius_m) : t.radius_m;
    o.clearance_m = avoidance_.robot_radius_m + o.radius_m + op.dynamic_obstacle_dist_m;
    o.growth_mps = op.dynamic_obstacle_growth_mps;
    o.lead_s = op.dynamic_obstacle_lead_s;
    if (o.usable()) out.push_back(o);  // a track with a non-finite state is left out
  }
  return out;
}

LocalPlanResult TebPlanner::plan(const Pose2& T_map_base, const Twist& current_velocity, const Path& global_plan,
                                 const mapping::Costmap2D& local_costmap, double now_s) {
  if (auto bad = reject_bad_inputs(T_map_base, current_velocity, global_plan, local_costmap)) return *bad;
  const Twist body = body_velocity(current_velocity);
  LocalPlanResult r;
  r.trajectory.frame_id = global_plan.frame_id;
  const Pose2 robot{T_map_base.x, T_map_base.y, normalize_angle(T_map_base.theta)};
  const GoalApproach ga = approach_goal(
      robot, global_plan.poses.back(), xy_goal_tolerance(params_.xy_goal_tolerance_m), params_.yaw_goal_tolerance_rad,
      params_.rotate_gain, params_.limits.velocity.max_vel_theta_radps, params_.xy_goal_release_m, &holding_goal_);
  if (ga.near) {
    // Turn on the spot to the goal yaw; the band is not needed any more.
    homotopy_.reset();
    r.goal_reached = ga.reached;
    r.result.message = ga.reached ? "goal reached" : "rotating to the goal yaw";
    r.trajectory.poses = {robot};
    r.trajectory.times_s = {0.0};
    return finish(std::move(r), ga.cmd, body);
  }
  const LocalGoal lg = select_local_goal(global_plan, robot, local_costmap, params_.lookahead_m,
                                         params_.window_margin_m, params_.via_point_separation_m);
  obstacles_ = extract_obstacles(local_costmap, params_.obstacles, &obstacle_scratch_);
  homotopy_.set_moving_obstacles(band_moving(now_s));
  const BandCandidate* best = homotopy_.plan(robot, lg.goal, body, lg.via_points, obstacles_);
  if (best == nullptr) {
    r.result = {Outcome::NO_VALID_CMD, "no candidate trajectory could be optimised"};
    return finish(std::move(r), {}, body);
  }
  r.trajectory = best->band.to_path(global_plan.frame_id);
  const std::size_t n_check =
      std::min(best->band.size(), static_cast<std::size_t>(params_.feasibility_check_poses) + 1);
  const std::vector<Pose2> head(best->band.poses.begin(), best->band.poses.begin() + static_cast<long>(n_check));
  if (!poses_feasible(head, local_costmap)) {
    homotopy_.reset();  // start afresh next cycle: the warm start led into an obstacle
    r.result = {Outcome::BLOCKED_PATH, "the best trajectory enters lethal or inscribed cells"};
    return finish(std::move(r), {}, body);
  }
  const Twist desired = band_command(best->band);
  r.result.message = "ok";
  return finish(std::move(r), desired, body);
}

}  // namespace bipednav::planning::local
