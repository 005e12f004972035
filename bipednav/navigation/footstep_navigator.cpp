#include "bipednav/navigation/footstep_navigator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "bipednav/navigation/obstacle_margin.hpp"

namespace bipednav::navigation {

using planning::footstep::Footstep;
using planning::footstep::FootstepPlan;

void FootstepNavigatorParams::validate() const {
  planner.validate();
  fusion.validate();
  odometry.validate();
  require(gicp_voxel_m > 0.0, "gicp_voxel_m", "> 0");
  require(replan_deviation_m > 0.0, "replan_deviation_m", "> 0");
  require(replan_deviation_rad > 0.0, "replan_deviation_rad", "> 0");
  require(max_plans >= 1, "max_plans", ">= 1");
  require(obstacle_margin_m >= 0.0, "obstacle_margin_m", ">= 0");
  require(obstacle_step_m > 0.0, "obstacle_step_m", "> 0");
}

planning::footstep::FootstepPlannerParams FootstepNavigatorParams::default_planner() {
  planning::footstep::FootstepPlannerParams p;
  p.robot = "nao";
  p.goal_tolerance_m = 0.05;
  p.goal_tolerance_rad = 0.15;
  // No landing margin (FootstepPlannerParams::landing_margin_m): step_onto and step_over leave
  // 2 cm between the stance toe and the landing heel, so a margin that covers the loop's
  // centimetre-level execution error would leave them no foothold; 1 cm did not help over seeds
  // 1-10 of nao_stairs. The loop recovers instead (max_recovery_steps).
  p.landing_margin_m = 0.0;
  p.search.initial_epsilon = 3.0;
  p.search.target_epsilon = 3.0;
  p.search.time_limit_s = 0.0;
  p.search.max_expansions = 2'000'000;
  return p;
}

localization::CorrectedOdometryParams FootstepNavigatorParams::default_odometry() {
  localization::CorrectedOdometryParams p;
  p.gicp.max_correspondence_m = 0.1;
  p.max_correction_step_m = 0.03;
  p.max_correction_step_rad = 0.03;
  return p;
}

FootstepNavigator::FootstepNavigator(const FootstepNavigatorParams& params, const mapping::GridGeometry& map_geometry)
    : params_(params),
      planner_((params.validate(), params.planner)),
      fusion_(map_geometry, params.fusion),
      odometry_(params.odometry, SE3::Identity()),  // merged clouds are given in the base frame
      voxel_(
          perception::VoxelGridParams{Eigen::Vector3d(params.gicp_voxel_m, params.gicp_voxel_m, params.gicp_voxel_m)}) {
}

void FootstepNavigator::set_goal(const Pose2& goal_map) {
  if (!goal_map.is_finite()) throw Error("FootstepNavigator::set_goal: non-finite goal");
  goal_ = goal_map;
  has_goal_ = true;
  plan_ = {};
  cursor_ = 0;
}

namespace {

void append_transformed(const PointCloud& in, const SE3& T, std::vector<Eigen::Vector3f>& out) {
  const Eigen::Matrix3f R = T.rotation().cast<float>();
  const Eigen::Vector3f t = T.translation().cast<float>();
  for (const auto& p : in.points)
    if (p.allFinite()) out.push_back(R * p + t);
}

}  // namespace

void FootstepNavigator::observe(const std::vector<DepthView>& views, const SE3& T_odom_base) {
  if (params_.gicp_correction) {
    PointCloud merged;  // base frame
    for (const DepthView& v : views) append_transformed(voxel_.filter(v.cloud_sensor), v.T_base_sensor, merged.points);
    corrections_ += odometry_.update(T_odom_base, voxel_.filter(merged)).corrected;
  }
  for (const DepthView& v : views) {
    const SE3 T_map_sensor = T_map_odom() * T_odom_base * v.T_base_sensor;
    std::vector<Eigen::Vector3f> points;
    points.reserve(v.cloud_sensor.size());
    append_transformed(v.cloud_sensor, T_map_sensor, points);
    fusion_.update(points, T_map_sensor.translation());
  }
  map_changed_ = true;
  planning_map_stale_ = true;
}

const mapping::Heightmap& FootstepNavigator::planning_map() {
  if (planning_map_stale_) {
    planning_map_ = inflate_obstacles(fusion_.map(), params_.obstacle_margin_m, params_.obstacle_step_m);
    planning_map_stale_ = false;
  }
  return planning_map_;
}

Footstep FootstepNavigator::to_map(const Footstep& odom) const {
  const SE3 T = T_map_odom() * se3_from_pose2(odom.pose, odom.z_m);
  return {pose2_from_se3(T), T.translation().z(), odom.foot};
}

FootstepPlan FootstepNavigator::remaining() const {
  FootstepPlan rest;
  rest.steps.assign(plan_.steps.begin() + static_cast<std::ptrdiff_t>(cursor_), plan_.steps.end());
  rest.actions.assign(plan_.actions.begin() + static_cast<std::ptrdiff_t>(cursor_), plan_.actions.end());
  return rest;
}

bool FootstepNavigator::close_to_plan(const Footstep& stance) const {
  const Footstep& planned = plan_.steps[cursor_];
  return planned.foot == stance.foot && distance(planned.pose, stance.pose) <= params_.replan_deviation_m &&
         std::abs(angle_diff(planned.pose.theta, stance.pose.theta)) <= params_.replan_deviation_rad;
}

bool FootstepNavigator::needs_replan(const Footstep& stance, std::optional<double> swing_z) {
  if (plan_.steps.empty() || cursor_ + 1 >= plan_.steps.size() || !close_to_plan(stance)) return true;
  if (!map_changed_) return false;
  map_changed_ = false;
  return !planner_.still_valid(planning_map(), remaining(), swing_z);
}

Result FootstepNavigator::replan(const Footstep& stance, std::optional<double> swing_z) {
  if (plans_ >= params_.max_plans)
    return {Outcome::PLAN_FAILURE, "gave up after " + std::to_string(plans_) + " footstep plans"};
  ++plans_;
  map_changed_ = false;
  // Where the plan put the stance foot, when the estimate is within the deviation thresholds of
  // it: the fallback start when the estimate itself is a dead end (a heel estimated a centimetre
  // closer to a riser than it is leaves no safe action).
  std::optional<Footstep> planned;
  if (!plan_.steps.empty() && cursor_ < plan_.steps.size() && close_to_plan(stance)) planned = plan_.steps[cursor_];
  plan_ = planner_.plan(planning_map(), stance, goal_, swing_z);
  if (!plan_.result.ok() && planned && plan_.result.outcome != Outcome::BLOCKED_GOAL) {
    FootstepPlan retry = planner_.plan(planning_map(), *planned, goal_, swing_z);
    if (retry.result.ok()) plan_ = std::move(retry);
  }
  cursor_ = 0;
  if (!plan_.result.ok()) {
    char where[160];
    std::snprintf(where, sizeof where, " (from the %s foot at %.3f, %.3f, %.3f rad, z %.3f m)", foot_name(stance.foot),
                  stance.pose.x, stance.pose.y, stance.pose.theta, stance.z_m);
    plan_.result.message += where;
  }
  return plan_.result;
}

bool FootstepNavigator::recover(const Footstep& stance, std::optional<double> swing_z) {
  // Within the planning map a plan that fails from a stance also fails from every step the
  // graph could take from it: one corrective planar step is taken, the head looks again and the
  // next decision replans from where the foot really landed (a centimetre or two elsewhere, seen
  // anew). Steps that move the feet away from what blocks them come first.
  static constexpr const char* kOrder[] = {"back_4",   "in_place",    "back_turn_out", "turn_in",
                                           "turn_out", "fwd_turn_in", "side_out",      "fwd_turn_out",
                                           "fwd_4",    "diag_out",    "long_out",      "fwd_8"};
  // The obstacle margin is a planning buffer that execution error may already have put the
  // stance inside (sideways in a narrow gap, an arm within 3 cm of a wall). Then the corrective
  // step is checked against the map as measured, without the margin, and the first of a few
  // candidates from whose landing the planner (with the margin) reaches the goal is preferred.
  auto safe = planner_.safe_steps(planning_map(), stance, swing_z);
  const bool inside_margin = safe.empty();
  if (inside_margin) safe = planner_.safe_steps(fusion_.map(), stance, swing_z);
  std::vector<const std::pair<std::string, Footstep>*> candidates;
  for (const char* name : kOrder)
    for (const auto& s : safe)
      if (s.first == name) candidates.push_back(&s);
  for (const auto& s : safe) {  // other action sets: their planar actions
    if (std::find(candidates.begin(), candidates.end(), &s) != candidates.end()) continue;
    for (const auto& a : planner_.lattice().actions().actions)
      if (a.name == s.first && a.kind == planning::footstep::ActionKind::kPlanar) candidates.push_back(&s);
  }
  if (candidates.empty()) return false;
  const std::pair<std::string, Footstep>* step = candidates.front();
  if (inside_margin) {
    for (std::size_t i = 0; i < std::min<std::size_t>(candidates.size(), 4); ++i) {
      // After the corrective step the old stance foot is the swing foot.
      if (planner_.plan(planning_map(), candidates[i]->second, goal_, stance.z_m).result.ok()) {
        step = candidates[i];
        break;
      }
    }
  }
  plan_ = {};
  plan_.steps = {stance, step->second};
  plan_.actions = {step->first};
  plan_.result = {Outcome::SUCCESS, "recovery step '" + step->first + "', then a replan from where it lands"};
  cursor_ = 0;
  ++recoveries_;
  ++recoveries_in_row_;
  return true;
}

StepDecision FootstepNavigator::next(const Footstep& odom_stance, const std::optional<Footstep>& odom_swing) {
  StepDecision d;
  if (!has_goal_) {
    d.done = true;
    d.result = {Outcome::INVALID_GOAL, "no goal given"};
    return d;
  }
  const Footstep stance = to_map(odom_stance);
  std::optional<double> swing_z;
  if (odom_swing) swing_z = to_map(*odom_swing).z_m;
  const double half = planner_.lattice().actions().body.nominal_separation_m / 2.0;
  // The body centre as the planner defines it: half a separation from the stance foot.
  const Pose2 body = stance.pose * Pose2{0.0, stance.foot == planning::footstep::Foot::kLeft ? -half : half, 0.0};
  const bool finished = !plan_.steps.empty() && cursor_ + 1 >= plan_.steps.size();
  if (finished && distance(body, goal_) <= params_.planner.goal_tolerance_m + params_.replan_deviation_m &&
      std::abs(angle_diff(body.theta, goal_.theta)) <= params_.planner.goal_tolerance_rad) {
    d.done = true;
    d.result = {Outcome::SUCCESS, "goal reached after " + std::to_string(plans_) + " plans"};
    return d;
  }
  if (needs_replan(stance, swing_z)) {
    d.replanned = true;
    d.result = replan(stance, swing_z);
    if (d.result.ok()) {
      recoveries_in_row_ = 0;
    } else if (d.result.outcome == Outcome::NO_PATH_FOUND && recoveries_in_row_ < params_.max_recovery_steps &&
               recover(stance, swing_z)) {
      d.result = plan_.result;
    }
    if (!d.result.ok() || plan_.actions.empty()) {
      d.done = true;
      if (d.result.ok()) d.result = {Outcome::SUCCESS, "already at the goal"};
      return d;
    }
  }
  d.target = plan_.steps[cursor_ + 1];
  for (const auto& a : planner_.lattice().actions().actions)
    if (a.name == plan_.actions[cursor_]) d.action = &a;
  if (!d.action) throw Error("FootstepNavigator: plan names an unknown action '" + plan_.actions[cursor_] + "'");
  ++cursor_;
  return d;
}

}  // namespace bipednav::navigation
