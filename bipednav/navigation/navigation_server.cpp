#include "bipednav/navigation/navigation_server.hpp"

#include <algorithm>
#include <cmath>

#include "bipednav/common/cpu_time.hpp"
#include "bipednav/planning/global/global_planner_factory.hpp"
#include "bipednav/planning/local/local_planner_factory.hpp"

namespace bipednav::navigation {

void ServerParams::validate() const {
  global.validate();
  local.validate();
  goal.validate();
  progress.validate();
  oscillation.validate();
  // The planner factories check the names too, but only when the server is built.
  require(global_planner == "dstar_lite" || global_planner == "astar", "global_planner", "dstar_lite or astar");
  require(local_planner == "teb" || local_planner == "tracker", "local_planner", "teb or tracker");
  require(controller_failures_allowed >= 0, "controller_failures_allowed", ">= 0");
  require(blocked_goal_timeout_s >= 0.0, "blocked_goal_timeout_s", ">= 0");
  require(path_check_distance_m > 0.0, "path_check_distance_m", "> 0");
  require(relaxed_cost_weight_factor > 0.0 && relaxed_cost_weight_factor <= 1.0, "relaxed_cost_weight_factor",
          "in (0, 1]");
  require(controller_goal_tolerance_fraction >= 0.0 && controller_goal_tolerance_fraction <= 1.0,
          "controller_goal_tolerance_fraction", "in [0, 1]");
  require(min_controller_goal_tolerance_fraction > 0.0 && min_controller_goal_tolerance_fraction <= 1.0,
          "min_controller_goal_tolerance_fraction", "in (0, 1]");
  require(std::isfinite(plan_clearance_sigmas) && plan_clearance_sigmas >= 0.0 && plan_clearance_sigmas <= 10.0,
          "plan_clearance_sigmas", "in [0, 10]");
  require(planning_recoveries_allowed >= 0, "planning_recoveries_allowed", ">= 0");
}

double plan_clearance_allowance_m(const ServerParams& params, double position_sigma_m) {
  // Whole centimetres: the planner starts its search afresh when the allowance changes, so a
  // slowly growing sigma changes it in steps.
  return std::ceil(params.plan_clearance_sigmas * std::max(0.0, position_sigma_m) * 100.0 - 1e-9) / 100.0;
}

void apply_controller_goal_tolerances(ServerParams& params) {
  const double f = params.controller_goal_tolerance_fraction;
  if (!(f > 0.0)) return;
  const double xy = f * params.goal.xy_tolerance_m, yaw = f * params.goal.yaw_tolerance_rad;
  params.local.teb.xy_goal_tolerance_m = params.local.tracker.xy_goal_tolerance_m = xy;
  params.local.teb.yaw_goal_tolerance_rad = params.local.tracker.yaw_goal_tolerance_rad = yaw;
  params.local.teb.xy_goal_release_m = params.local.tracker.xy_goal_release_m = params.goal.xy_tolerance_m;
}

NavigationServer::NavigationServer(ServerParams params, RobotProfile robot, mapping::GlobalCostmap& global,
                                   mapping::LocalCostmap& local, const planning::local::MovingObstacleTracker* moving)
    : params_(std::move(params)),
      robot_(std::move(robot)),
      limits_((robot_.limits.validate(), robot_.limits)),
      global_(global),
      local_(local),
      goal_checker_(params_.goal),
      progress_(params_.progress),
      oscillation_(params_.oscillation) {
  params_.validate();
  apply_controller_goal_tolerances(params_);
  make_global_planner(false);
  local_planner_ = planning::local::make_local_planner(params_.local_planner, params_.local, moving);
}

void NavigationServer::make_global_planner(bool relaxed) {
  planning::global::GlobalPlannerParams p = params_.global;
  if (relaxed) p.cost.cost_weight *= params_.relaxed_cost_weight_factor;
  p.cost.min_impassable_cost = impassable_cost_;
  global_planner_ = planning::global::make_global_planner(params_.global_planner, p);
  relaxed_ = relaxed;
  pending_changes_.clear();
}

void NavigationServer::add_global_changes(const mapping::ChangeSet& changes) {
  pending_changes_.insert(pending_changes_.end(), changes.begin(), changes.end());
}

void NavigationServer::on_new_goal() {
  if (relaxed_) make_global_planner(false);
  goal_checker_.reset();
  local_planner_->reset();
  ctrl_failures_ = 0;
  planning_recoveries_ = 0;
}

bool NavigationServer::admit_planning_recovery() {
  if (planning_recoveries_ >= params_.planning_recoveries_allowed) return false;
  ++planning_recoveries_;
  return true;
}

int NavigationServer::plan_impassable_cost() const {
  const mapping::InflationParams inflation = global_.params().inflation();
  const double allowance_m = plan_clearance_allowance_m(params_, view_.position_sigma_m);
  return planning::global::min_impassable_cost(inflation.inscribed_radius_m + allowance_m, inflation);
}

planning::global::PlanResult NavigationServer::get_path(const Pose2& goal) {
  // A changed clearance changes which cells are passable everywhere: a fresh search.
  if (const int c = plan_impassable_cost(); c != impassable_cost_) {
    impassable_cost_ = c;
    make_global_planner(relaxed_);
  }
  {
    const CpuScope cpu(global_planner_cpu_ms_);
    last_plan_ = global_planner_->plan(global_.costmap(), view_.pose, goal, pending_changes_);
  }
  pending_changes_.clear();
  ++plans_;
  return last_plan_;
}

ActionStep NavigationServer::exe_path(const Path& path, bool first) {
  if (first) {
    progress_.reset();
    oscillation_.reset();
    ctrl_failures_ = 0;
  }
  if (path.empty()) {
    cmd_ = {};
    return {ActionStep::State::FAILED, {Outcome::INVALID_PATH, "exe_path got an empty path"}};
  }
  // A goal that stays inside an obstacle cannot be reached by following the path; a moving
  // obstacle passing over it only makes the robot wait.
  if (const Result g = goal_valid(path.poses.back()); g.outcome == Outcome::BLOCKED_GOAL) {
    if (blocked_since_s_ < 0.0) blocked_since_s_ = view_.now_s;
    if (view_.now_s - blocked_since_s_ >= params_.blocked_goal_timeout_s) {
      cmd_ = {};
      return {ActionStep::State::FAILED, {Outcome::CTRL_BLOCKED_GOAL, g.message}};
    }
  } else {
    blocked_since_s_ = -1.0;
  }
  if (goal_reached(path.poses.back())) {
    cmd_ = {};
    return {ActionStep::State::SUCCEEDED, {Outcome::SUCCESS, "goal reached"}};
  }
  local_planner_->set_xy_goal_tolerance(controller_xy_goal_tolerance());
  planning::local::LocalPlanResult r;
  {
    const CpuScope cpu(local_planner_cpu_ms_);
    r = local_planner_->compute(view_.pose, view_.velocity, path, local_.costmap(), view_.now_s);
  }
  trajectory_ = r.trajectory;
  cmd_ = r.result.ok() ? r.cmd : Twist{};
  if (!r.result.ok()) {
    if (++ctrl_failures_ > params_.controller_failures_allowed) return {ActionStep::State::FAILED, r.result};
    return {};
  }
  ctrl_failures_ = 0;
  if (!progress_.check(view_.pose, view_.now_s)) {
    cmd_ = {};
    return {ActionStep::State::FAILED, {Outcome::ROBOT_STUCK, "no progress within the progress checker's window"}};
  }
  if (oscillation_.check(cmd_, view_.pose, view_.now_s)) {
    cmd_ = {};
    return {ActionStep::State::FAILED, {Outcome::OSCILLATION, "the commands oscillate without progress"}};
  }
  return {};
}

void NavigationServer::begin_recovery(const char* name) {
  if (recovery_running()) end_recovery(Result{Outcome::RECOVERY_CANCELED, std::string("superseded by ") + name});
  ++recoveries_;
  if (recovery_log_.size() == kRecoveryLogSize) recovery_log_.erase(recovery_log_.begin());
  recovery_log_.push_back({name, view_.now_s, -1.0, {}});
  recovery_start_pose_ = view_.pose;
  recovery_start_s_ = view_.now_s;
}

Result NavigationServer::end_recovery(Result result) {
  if (recovery_running()) {
    recovery_log_.back().end_s = view_.now_s;
    recovery_log_.back().result = result;
  }
  return result;
}

ActionStep NavigationServer::end_recovery(ActionStep step) {
  if (step.state != ActionStep::State::RUNNING) step.result = end_recovery(std::move(step.result));
  return step;
}

void NavigationServer::cancel_recovery() {
  cmd_ = {};
  if (recovery_running()) end_recovery(Result{Outcome::RECOVERY_CANCELED, "halted by the behavior tree"});
}

Twist NavigationServer::ramp_to(const Twist& target) const {
  return limit_velocity(target, view_.velocity, view_.period_s, limits_);
}

ActionStep NavigationServer::back_up(double distance_m, double speed_mps, bool first) {
  using State = ActionStep::State;
  if (first) begin_recovery("BackUp");
  cmd_ = {};
  if (robot_.limits.max_vel_x_backwards_mps <= 0.0)
    return end_recovery({State::FAILED, {Outcome::RECOVERY_FAILURE, "this robot cannot walk backwards"}});
  // Refuse to back into an obstacle: probe just behind the footprint.
  const Pose2 probe = view_.pose * Pose2{-(robot_.footprint_radius_m + 0.1), 0.0, 0.0};
  const auto& lc = local_.costmap();
  if (auto c = lc.geometry().world_to_cell(probe.x, probe.y); c && lc.cost(*c) >= mapping::kInscribed)
    return end_recovery({State::FAILED, {Outcome::RECOVERY_IMPASSABLE, "an obstacle is behind the robot"}});
  const double speed = std::min(speed_mps, robot_.limits.max_vel_x_backwards_mps);
  if (distance(view_.pose, recovery_start_pose_) >= distance_m)
    return end_recovery({State::SUCCEEDED, {Outcome::SUCCESS, "backed up"}});
  if (view_.now_s - recovery_start_s_ > 2.0 * distance_m / speed + 2.0)
    return end_recovery({State::FAILED, {Outcome::RECOVERY_PAT_EXCEEDED, "backing up took too long"}});
  cmd_ = ramp_to({-speed, 0.0, 0.0});
  return {};
}

ActionStep NavigationServer::rotate_in_place(double angle_rad, bool first) {
  using State = ActionStep::State;
  if (first) {
    begin_recovery("RotateInPlace");
    rotated_rad_ = 0.0;
    last_yaw_ = view_.pose.theta;
  }
  cmd_ = {};
  if (!robot_.can_rotate_in_place)
    return end_recovery({State::FAILED, {Outcome::RECOVERY_FAILURE, "this robot cannot rotate in place"}});
  rotated_rad_ += std::abs(angle_diff(view_.pose.theta, last_yaw_));
  last_yaw_ = view_.pose.theta;
  if (rotated_rad_ >= std::abs(angle_rad)) return end_recovery({State::SUCCEEDED, {Outcome::SUCCESS, "rotated"}});
  const double rate = 0.6 * robot_.limits.max_vel_theta_radps;
  if (view_.now_s - recovery_start_s_ > 2.0 * std::abs(angle_rad) / rate + 2.0)
    return end_recovery({State::FAILED, {Outcome::RECOVERY_PAT_EXCEEDED, "rotating took too long"}});
  cmd_ = ramp_to({0.0, 0.0, angle_rad >= 0.0 ? rate : -rate});
  return {};
}

ActionStep NavigationServer::wait(double duration_s, bool first) {
  if (first) begin_recovery("Wait");
  cmd_ = {};
  if (view_.now_s - recovery_start_s_ >= duration_s)
    return end_recovery({ActionStep::State::SUCCEEDED, {Outcome::SUCCESS, "waited"}});
  return {};
}

Result NavigationServer::clear_costmaps() {
  begin_recovery("ClearCostmaps");
  // The local map only: the global map keeps what the LiDAR saw of walls and obstacles (its
  // own ray-trace clearing removes stale cells), so a blocked goal stays known as blocked.
  local_.clear();
  local_planner_->reset();
  return end_recovery({Outcome::SUCCESS, "local costmap cleared"});
}

Result NavigationServer::relax_constraints() {
  begin_recovery("RelaxConstraints");
  if (relaxed_) return end_recovery({Outcome::RECOVERY_FAILURE, "constraints are already relaxed"});
  make_global_planner(true);
  return end_recovery({Outcome::SUCCESS, "planner cost weight relaxed"});
}

double NavigationServer::controller_xy_goal_tolerance() const {
  const double tolerance_m = params_.goal.xy_tolerance_m;
  const double aim_m = local_planner_->aimed_xy_goal_tolerance_m();
  const double budget_m = tolerance_m - 2.0 * view_.position_sigma_m;
  return std::min(aim_m, std::max(params_.min_controller_goal_tolerance_fraction * tolerance_m, budget_m));
}

bool NavigationServer::goal_reached(const Pose2& goal) {
  return goal_checker_.reached(view_.pose, goal, view_.body_velocity.value_or(view_.velocity), view_.now_s);
}

Result NavigationServer::goal_valid(const Pose2& goal) const {
  if (!goal.is_finite()) return {Outcome::INVALID_GOAL, "the goal is not finite"};
  const auto& map = global_.costmap();
  const auto c = map.geometry().world_to_cell(goal.x, goal.y);
  if (!c) return {Outcome::PLAN_OUT_OF_MAP, "the goal is outside the global map"};
  const std::uint8_t cost = map.cost(*c);
  // A goal too near an obstacle for the planner (inscribed, or within its clearance allowance) with
  // a cell it may enter within its goal tolerance stays valid: the path ends there
  // (GlobalPlannerParams::goal_tolerance_m).
  planning::global::GlobalPlannerParams planner = params_.global;
  planner.cost.min_impassable_cost = plan_impassable_cost();
  if (cost == mapping::kLethal ||
      (cost >= planner.cost.min_impassable_cost && !planning::global::goal_search_cell(map, goal, planner)))
    return {Outcome::BLOCKED_GOAL, "the goal lies in or too close to an obstacle"};
  return {Outcome::SUCCESS, ""};
}

Result NavigationServer::start_valid() const {
  if (!view_.pose.is_finite()) return {Outcome::INVALID_START, "the robot's pose is not finite"};
  const auto& map = global_.costmap();
  const auto c = map.geometry().world_to_cell(view_.pose.x, view_.pose.y);
  if (!c) return {Outcome::INVALID_START, "the robot is outside the global map"};
  if (map.cost(*c) == mapping::kLethal) return {Outcome::BLOCKED_START, "the robot's centre lies in an obstacle"};
  return {Outcome::SUCCESS, ""};
}

bool NavigationServer::path_valid(const Path& path) const {
  if (path.empty()) return false;
  const auto& map = global_.costmap();
  double travelled = 0.0;
  // Only the stretch ahead of the robot matters; the part behind it may be stale.
  std::size_t start = 0;
  double best = 1e300;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const double d = distance(path.poses[i], view_.pose);
    if (d < best) best = d, start = i;
  }
  for (std::size_t i = start; i < path.size() && travelled <= params_.path_check_distance_m; ++i) {
    if (i > start) travelled += distance(path.poses[i - 1], path.poses[i]);
    const auto c = map.geometry().world_to_cell(path.poses[i].x, path.poses[i].y);
    if (c && map.cost(*c) == mapping::kLethal) return false;
  }
  return true;
}

}  // namespace bipednav::navigation
