#pragma once

// The field lists (navigator_params_yaml.cpp) of the planning and control parameters of NavigatorParams
// (the global and local planners, the controller's checkers, the navigation server) and of its top level.
#include "bipednav/navigation/navigator.hpp"
#include "bipednav/planning/local/moving_obstacle_yield.hpp"

namespace bipednav::navigation::param_fields {

// Fields that two structs share under the same names, listed once.

// TEB's and the path tracker's velocity and acceleration limits.
template <class V, class Planner>
void visit_velocity_limits(V& v, Planner& p) {
  v("max_vel_x_mps", p.max_vel_x_mps);
  v("max_vel_x_backwards_mps", p.max_vel_x_backwards_mps);
  v("max_vel_theta_radps", p.max_vel_theta_radps);
  v("acc_lim_x_mps2", p.acc_lim_x_mps2);
  v("acc_lim_theta_radps2", p.acc_lim_theta_radps2);
}

// How TEB and the path tracker finish at the goal (apply_controller_goal_tolerances sets the
// first three from the goal checker's tolerances).
template <class V, class Planner>
void visit_goal_approach(V& v, Planner& p) {
  v("xy_goal_tolerance_m", p.xy_goal_tolerance_m);
  v("yaw_goal_tolerance_rad", p.yaw_goal_tolerance_rad);
  v("xy_goal_release_m", p.xy_goal_release_m);
  v("rotate_gain", p.rotate_gain);
  v("control_period_s", p.control_period_s);
}

template <class V>
void visit_fields(V& v, planning::GridCostParams& p) {
  v("cost_weight", p.cost_weight);
  v("unknown_is_obstacle", p.unknown_is_obstacle);
  v("unknown_cost", p.unknown_cost);
}

template <class V>
void visit_fields(V& v, planning::GlobalPlannerParams& p) {
  v.group("cost", p.cost);
  v("allow_start_in_inscribed", p.allow_start_in_inscribed);
  v("goal_tolerance_m", p.goal_tolerance_m);
  v("max_planning_time_ms", p.max_planning_time_ms);
  v("verify_changes", p.verify_changes);
}

template <class V>
void visit_fields(V& v, planning::local::TebLimits& p) {
  visit_velocity_limits(v, p);
  v("min_obstacle_dist_m", p.min_obstacle_dist_m);
}

template <class V>
void visit_fields(V& v, planning::local::TebBandParams& p) {
  v("dt_ref_s", p.dt_ref_s);
  v("dt_hysteresis_s", p.dt_hysteresis_s);
  v("min_samples", p.min_samples);
  v("max_samples", p.max_samples);
  v("dt_min_s", p.dt_min_s);
  v("reinit_goal_dist_m", p.reinit_goal_dist_m);
  v("reinit_goal_angle_rad", p.reinit_goal_angle_rad);
}

template <class V>
void visit_fields(V& v, planning::local::TebOptimizerParams& p) {
  v("weight_optimaltime", p.weight_optimaltime);
  v("weight_kinematics_nh", p.weight_kinematics_nh);
  v("weight_backwards", p.weight_backwards);
  v("weight_max_vel_x", p.weight_max_vel_x);
  v("weight_max_vel_theta", p.weight_max_vel_theta);
  v("weight_acc_lim_x", p.weight_acc_lim_x);
  v("weight_acc_lim_theta", p.weight_acc_lim_theta);
  v("weight_obstacle", p.weight_obstacle);
  v("weight_viapoint", p.weight_viapoint);
  v("weight_adapt_factor", p.weight_adapt_factor);
  v("penalty_epsilon", p.penalty_epsilon);
  v("sign_gain", p.sign_gain);
  v("no_inner_iterations", p.no_inner_iterations);
  v("no_outer_iterations", p.no_outer_iterations);
  v("function_tolerance", p.function_tolerance);
  v("obstacles_per_pose", p.obstacles_per_pose);
  v("obstacle_influence_dist_m", p.obstacle_influence_dist_m);
  v("dynamic_obstacles", p.dynamic_obstacles);
  v("weight_dynamic_obstacle", p.weight_dynamic_obstacle);
  v("dynamic_obstacle_dist_m", p.dynamic_obstacle_dist_m);
  v("dynamic_obstacle_max_prediction_s", p.dynamic_obstacle_max_prediction_s);
  v("dynamic_obstacle_growth_mps", p.dynamic_obstacle_growth_mps);
  v("dynamic_obstacle_lead_s", p.dynamic_obstacle_lead_s);
  v("dynamic_obstacle_largest_radius", p.dynamic_obstacle_largest_radius);
  v("linear_solver", p.linear_solver);
  v("ceres_sparse_library", p.ceres_sparse_library);
}

template <class V>
void visit_fields(V& v, planning::local::ObstacleParams& p) {
  v("point_max_extent_m", p.point_max_extent_m);
  v("line_max_width_m", p.line_max_width_m);
  v("cluster_block_m", p.cluster_block_m);
  v("max_obstacles", p.max_obstacles);
}

template <class V>
void visit_fields(V& v, planning::local::HomotopyParams& p) {
  v("enabled", p.enabled);
  v("max_classes", p.max_classes);
  v("num_threads", p.num_threads);
  v("selection_hysteresis", p.selection_hysteresis);
  v("corridor_halfwidth_m", p.corridor_halfwidth_m);
  v("max_keypoint_obstacles", p.max_keypoint_obstacles);
  v("keypoint_margin_m", p.keypoint_margin_m);
  v("max_path_expansions", p.max_path_expansions);
  v("roadmap_clearance_ratio", p.roadmap_clearance_ratio);
  v("max_cost_ratio", p.max_cost_ratio);
  v("signature_tolerance_rad", p.signature_tolerance_rad);
}

template <class V>
void visit_fields(V& v, planning::local::TebBodyResponse& p) {
  v("time_constant_s", p.time_constant_s);
  v("horizon_s", p.horizon_s);
}

template <class V>
void visit_fields(V& v, planning::local::TebParams& p) {
  v.group("limits", p.limits);
  v.group("band", p.band);
  v.group("optim", p.optim);
  v.group("obstacles", p.obstacles);
  v.group("homotopy", p.homotopy);
  v.group("response", p.response);
  v("lookahead_m", p.lookahead_m);
  v("window_margin_m", p.window_margin_m);
  v("via_point_separation_m", p.via_point_separation_m);
  visit_goal_approach(v, p);
  v("feasibility_check_poses", p.feasibility_check_poses);
  v("oscillation_window", p.oscillation_window);
}

template <class V>
void visit_fields(V& v, planning::local::TrackerParams& p) {
  v("lookahead_m", p.lookahead_m);
  visit_velocity_limits(v, p);
  v("rotate_in_place_angle_rad", p.rotate_in_place_angle_rad);
  visit_goal_approach(v, p);
  v("collision_check_horizon_s", p.collision_check_horizon_s);
}

template <class V>
void visit_fields(V& v, planning::local::DynamicAvoidanceParams& p) {
  v("horizon_s", p.horizon_s);
  v("robot_radius_m", p.robot_radius_m);
  v("safety_margin_m", p.safety_margin_m);
  v("prediction_growth_mps", p.prediction_growth_mps);
  v("sim_step_s", p.sim_step_s);
  v("static_check_s", p.static_check_s);
  v("hold_step_s", p.hold_step_s);
}

template <class V>
void visit_fields(V& v, planning::local::LocalPlannerParams& p) {
  v.group("teb", p.teb);
  v.group("tracker", p.tracker);
  v.group("avoidance", p.avoidance);
}

template <class V>
void visit_fields(V& v, control::GoalCheckerParams& p) {
  v("xy_tolerance_m", p.xy_tolerance_m);
  v("yaw_tolerance_rad", p.yaw_tolerance_rad);
  v("check_yaw", p.check_yaw);
  v("stateful", p.stateful);
  v("require_stopped", p.require_stopped);
  v("trans_stopped_velocity_mps", p.trans_stopped_velocity_mps);
  v("rot_stopped_velocity_radps", p.rot_stopped_velocity_radps);
  v("stopped_timeout_s", p.stopped_timeout_s);
}

template <class V>
void visit_fields(V& v, control::ProgressCheckerParams& p) {
  v("required_movement_radius_m", p.required_movement_radius_m);
  v("movement_time_allowance_s", p.movement_time_allowance_s);
}

template <class V>
void visit_fields(V& v, control::OscillationCheckerParams& p) {
  v("window_s", p.window_s);
  v("max_sign_flips", p.max_sign_flips);
  v("min_net_progress_m", p.min_net_progress_m);
  v("sign_deadband", p.sign_deadband);
}

template <class V>
void visit_fields(V& v, ServerParams& p) {
  v("global_planner", p.global_planner);
  v.group("global", p.global);
  v("local_planner", p.local_planner);
  v.group("local", p.local);
  v.group("goal", p.goal);
  v("controller_goal_tolerance_fraction", p.controller_goal_tolerance_fraction);
  v("min_controller_goal_tolerance_fraction", p.min_controller_goal_tolerance_fraction);
  v.group("progress", p.progress);
  v.group("oscillation", p.oscillation);
  v("controller_failures_allowed", p.controller_failures_allowed);
  v("path_check_distance_m", p.path_check_distance_m);
  v("blocked_goal_timeout_s", p.blocked_goal_timeout_s);
  v("relaxed_cost_weight_factor", p.relaxed_cost_weight_factor);
  v("plan_clearance_sigmas", p.plan_clearance_sigmas);
  v("planning_recoveries_allowed", p.planning_recoveries_allowed);
}

// The top level: the navigator's own scalars first, then the components.
template <class V>
void visit_fields(V& v, NavigatorParams& p) {
  v("control_rate_hz", p.control_rate_hz);
  v("brake_from_last_command", p.brake_from_last_command);
  v("newest_depth_only", p.newest_depth_only);
  v("behavior_tree", p.behavior_tree);
  v.group("local_map", p.local_map);
  v.group("global_map", p.global_map);
  v.group("perception", p.perception);
  v.group("localization", p.localization);
  v.group("sensors", p.sensors);
  v.group("moving_obstacles", p.moving_obstacles);
  v.group("server", p.server);
}

}  // namespace bipednav::navigation::param_fields
