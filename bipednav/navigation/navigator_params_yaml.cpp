#include "bipednav/navigation/navigator_params_yaml.hpp"

#include <yaml-cpp/yaml.h>

#include <charconv>
#include <cmath>
#include <type_traits>
#include <vector>

#include "bipednav/planning/local/moving_obstacle_params.hpp"
#include "bipednav/planning/local/moving_obstacle_yield.hpp"

namespace bipednav::navigation {

namespace {

// One function per parameter struct lists its fields once, in the order of its declaration; the
// same list reads a file (ParamOverlay) and writes one (ParamDump), so the two cannot disagree.
// A visitor has operator()(key, field) for scalars, strings and Eigen vectors and
// group(key, nested_struct) for a nested mapping.

// Fields that two structs share under the same names, listed once.

// The inflation and obstacle-layer fields of both costmaps (inflation(), obstacle_layer()).
template <class V, class Costmap>
void visit_layer_fields(V& v, Costmap& p) {
  v("inscribed_radius_m", p.inscribed_radius_m);
  v("inflation_radius_m", p.inflation_radius_m);
  v("cost_scaling_factor", p.cost_scaling_factor);
  v("obstacle_max_range_m", p.obstacle_max_range_m);
  v("raytrace_max_range_m", p.raytrace_max_range_m);
  v("height_aware_clearing", p.height_aware_clearing);
}

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
void visit_fields(V& v, perception::VoxelGridParams& p) {
  v("leaf_size_m", p.leaf_size_m);
}

template <class V>
void visit_fields(V& v, perception::RansacParams& p) {
  v("distance_threshold_m", p.distance_threshold_m);
  v("success_probability", p.success_probability);
  v("max_iterations", p.max_iterations);
  v("use_normal_prior", p.use_normal_prior);
  v("max_normal_angle_rad", p.max_normal_angle_rad);
  v("refit", p.refit);
  v("inlier_std", p.inlier_std);
  v("max_points", p.max_points);
}

template <class V>
void visit_fields(V& v, perception::PerceptionParams& p) {
  v.group("depth_voxel", p.depth_voxel);
  v("depth_decimation", p.depth_decimation);
  v("depth_image_width", p.depth_image_width);
  v("depth_max_range_m", p.depth_max_range_m);
  v("lidar_min_range_m", p.lidar_min_range_m);
  v("lidar_max_range_m", p.lidar_max_range_m);
  v("lidar_voxel_m", p.lidar_voxel_m);
  v("deskew_lidar", p.deskew_lidar);
  v.group("ransac", p.ransac);
  v("prior_ground", p.prior_ground);
  v("max_ground_offset_m", p.max_ground_offset_m);
  v("min_ground_inliers", p.min_ground_inliers);
  v("min_obstacle_height_m", p.min_obstacle_height_m);
  v("obstacle_height_margin_m", p.obstacle_height_margin_m);
  v("seed", p.seed);
}

template <class V>
void visit_fields(V& v, localization::FeatureParams& p) {
  v("neighbours_per_side", p.neighbours_per_side);
  v("sub_regions", p.sub_regions);
  v("max_edges_per_region", p.max_edges_per_region);
  v("max_planars_per_region", p.max_planars_per_region);
  v("map_feature_factor", p.map_feature_factor);
  v("edge_threshold", p.edge_threshold);
  v("planar_threshold", p.planar_threshold);
  v("min_range_m", p.min_range_m);
  v("max_range_m", p.max_range_m);
  v("occlusion_ratio", p.occlusion_ratio);
  v("parallel_beam_ratio", p.parallel_beam_ratio);
  v("max_neighbour_gap_ratio", p.max_neighbour_gap_ratio);
  v("rings", p.rings);
  v("min_elevation_rad", p.min_elevation_rad);
  v("max_elevation_rad", p.max_elevation_rad);
}

template <class V>
void visit_fields(V& v, localization::AssociationParams& p) {
  v("neighbours", p.neighbours);
  v("max_correspondence_m", p.max_correspondence_m);
  v("max_plane_deviation_m", p.max_plane_deviation_m);
  v("min_line_ratio", p.min_line_ratio);
  v("edge_weight", p.edge_weight);
}

template <class V>
void visit_fields(V& v, localization::LmParams& p) {
  v("max_iterations", p.max_iterations);
  v("bisquare_c_m", p.bisquare_c_m);
  v("initial_lambda", p.initial_lambda);
  v("degenerate_min_eigenvalue", p.degenerate_min_eigenvalue);
  v("converged_translation_m", p.converged_translation_m);
  v("converged_rotation_rad", p.converged_rotation_rad);
}

template <class V>
void visit_fields(V& v, localization::OdometryParams& p) {
  v("scan_period_s", p.scan_period_s);
  v.group("association", p.association);
  v("correspondence_rounds", p.correspondence_rounds);
  v("relaxation", p.relaxation);
  v("round_converged_translation_m", p.round_converged_translation_m);
  v("round_converged_rotation_rad", p.round_converged_rotation_rad);
  v("min_constraints", p.min_constraints);
  v.group("lm", p.lm);
}

template <class V>
void visit_fields(V& v, localization::MappingParams& p) {
  v("rate_hz", p.rate_hz);
  v("edge_leaf_m", p.edge_leaf_m);
  v("planar_leaf_m", p.planar_leaf_m);
  v("map_radius_m", p.map_radius_m);
  v.group("association", p.association);
  v("correspondence_rounds", p.correspondence_rounds);
  v("round_converged_translation_m", p.round_converged_translation_m);
  v("round_converged_rotation_rad", p.round_converged_rotation_rad);
  v("min_constraints", p.min_constraints);
  v("gravity_weight", p.gravity_weight);
  v.group("lm", p.lm);
}

template <class V>
void visit_fields(V& v, localization::LoamParams& p) {
  v.group("features", p.features);
  v.group("odometry", p.odometry);
  v.group("mapping", p.mapping);
  v("min_features", p.min_features);
  v("planar_constant_velocity", p.planar_constant_velocity);
  v("reference_from_prior_change", p.reference_from_prior_change);
  v("max_prior_change_m", p.max_prior_change_m);
  v("max_prior_change_rad", p.max_prior_change_rad);
  v("max_prior_error_change_rad", p.max_prior_error_change_rad);
  v("planar_motion", p.planar_motion);
}

template <class V>
void visit_fields(V& v, LocalizerParams& p) {
  v("method", p.method);
  v.group("loam", p.loam);
  v("sweep_duration_s", p.sweep_duration_s);
  v("max_correction_jump_m", p.max_correction_jump_m);
  v("max_correction_jump_rad", p.max_correction_jump_rad);
  v("unhealthy_after_bad_sweeps", p.unhealthy_after_bad_sweeps);
  v("odometry_timeout_s", p.odometry_timeout_s);
  v("max_odometry_speed_mps", p.max_odometry_speed_mps);
  v("max_odometry_rate_radps", p.max_odometry_rate_radps);
}

template <class V>
void visit_fields(V& v, mapping::LocalCostmapParams& p) {
  v("size_m", p.size_m);
  v("resolution_m", p.resolution_m);
  visit_layer_fields(v, p);
  v("mark_decay_s", p.mark_decay_s);
  v("rate_hz", p.rate_hz);
}

template <class V>
void visit_fields(V& v, mapping::GlobalCostmapParams& p) {
  v("resolution_m", p.resolution_m);
  v("default_size_m", p.default_size_m);
  visit_layer_fields(v, p);
  v("lidar_clearing", p.lidar_clearing);
  v("merge_local", p.merge_local);
  v("mark_decay_s", p.mark_decay_s);
  v("unknown_cost_mode", p.unknown_cost_mode);
  v("rate_hz", p.rate_hz);
}

template <class V>
void visit_fields(V& v, SensorGateParams& p) {
  v("max_age_s", p.max_age_s);
  v("min_valid_ratio", p.min_valid_ratio);
  v("sensor_timeout_s", p.sensor_timeout_s);
}

template <class V>
void visit_fields(V& v, planning::local::MovingObstacleParams& p) {
  v("enabled", p.enabled);
  v("cluster_cell_m", p.cluster_cell_m);
  v("min_points", p.min_points);
  v("max_blob_radius_m", p.max_blob_radius_m);
  v("max_range_m", p.max_range_m);
  v("gate_m", p.gate_m);
  v("max_track_age_s", p.max_track_age_s);
  v("measurement_noise_m", p.measurement_noise_m);
  v("accel_noise_mps2", p.accel_noise_mps2);
  v("max_speed_mps", p.max_speed_mps);
  v("min_hits", p.min_hits);
  v("min_moving_speed_mps", p.min_moving_speed_mps);
  v("min_displacement_m", p.min_displacement_m);
  v("latch_displacement_m", p.latch_displacement_m);
  v("recent_motion", p.recent_motion);
  v("motion_window_s", p.motion_window_s);
  v("moving_pause_s", p.moving_pause_s);
  v("max_prediction_s", p.max_prediction_s);
  v("global_map_margin_m", p.global_map_margin_m);
  v("coast_in_blind_zone", p.coast_in_blind_zone);
  v("max_coast_s", p.max_coast_s);
  v("coast_max_growth_m", p.coast_max_growth_m);
  v("ignore_static_structure", p.ignore_static_structure);
  v("keep_largest_radius", p.keep_largest_radius);
  v("partial_view_noise", p.partial_view_noise);
  v("radius_floor", p.radius_floor);
  v("radius_floor_window_s", p.radius_floor_window_s);
  v("reacquire_gate_m", p.reacquire_gate_m);
  v("reacquire_coasting", p.reacquire_coasting);
  v("structure_age_s", p.structure_age_s);
  v("structure_margin_m", p.structure_margin_m);
  v("structure_min_fraction", p.structure_min_fraction);
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
  v("ceres_line_search_interpolation", p.ceres_line_search_interpolation);
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
void visit_fields(V& v, planning::local::TebParams& p) {
  v.group("limits", p.limits);
  v.group("band", p.band);
  v.group("optim", p.optim);
  v.group("obstacles", p.obstacles);
  v.group("homotopy", p.homotopy);
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
  v("exit_swept_corridor", p.exit_swept_corridor);
  v("reverse_at_structure", p.reverse_at_structure);
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
  v("prorate_partial_window", p.prorate_partial_window);
}

template <class V>
void visit_fields(V& v, ServerParams& p) {
  v("global_planner", p.global_planner);
  v.group("global", p.global);
  v("local_planner", p.local_planner);
  v.group("local", p.local);
  v.group("goal", p.goal);
  v("controller_goal_tolerance_fraction", p.controller_goal_tolerance_fraction);
  v.group("progress", p.progress);
  v.group("oscillation", p.oscillation);
  v("controller_failures_allowed", p.controller_failures_allowed);
  v("path_check_distance_m", p.path_check_distance_m);
  v("blocked_goal_timeout_s", p.blocked_goal_timeout_s);
  v("relaxed_cost_weight_factor", p.relaxed_cost_weight_factor);
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

// The footstep navigator (FootstepNavigatorParams).

template <class V>
void visit_fields(V& v, footstep::AraStarParams& p) {
  v("initial_epsilon", p.initial_epsilon);
  v("epsilon_decrease", p.epsilon_decrease);
  v("time_limit_s", p.time_limit_s);
  v("target_epsilon", p.target_epsilon);
  v("max_expansions", p.max_expansions);
}

template <class V>
void visit_fields(V& v, footstep::FootstepPlannerParams& p) {
  v("robot", p.robot);
  v("planar_only", p.planar_only);
  v("lattice_resolution_m", p.lattice_resolution_m);
  v("theta_bins", p.theta_bins);
  v("heuristic", p.heuristic);
  v("stance_level_heuristic", p.stance_level_heuristic);
  v("goal_tolerance_m", p.goal_tolerance_m);
  v("goal_tolerance_rad", p.goal_tolerance_rad);
  v("landing_margin_m", p.landing_margin_m);
  v("occlusion_rise_m", p.occlusion_rise_m);
  v.group("search", p.search);
}

template <class V>
void visit_fields(V& v, mapping::HeightmapFusionParams& p) {
  v("variance_per_m2", p.variance_per_m2);
  v("min_observation_variance_m2", p.min_observation_variance_m2);
  v("min_cell_variance_m2", p.min_cell_variance_m2);
  v("max_cell_variance_m2", p.max_cell_variance_m2);
  v("gate_sigma", p.gate_sigma);
  v("variance_growth_factor", p.variance_growth_factor);
  v("max_range_m", p.max_range_m);
}

template <class V>
void visit_fields(V& v, localization::GicpParams& p) {
  v("covariance_neighbours", p.covariance_neighbours);
  v("covariance_epsilon", p.covariance_epsilon);
  v("max_correspondence_m", p.max_correspondence_m);
  v("max_iterations", p.max_iterations);
  v("converged_translation_m", p.converged_translation_m);
  v("converged_rotation_rad", p.converged_rotation_rad);
  v("lm_lambda", p.lm_lambda);
  v("threads", p.threads);
}

template <class V>
void visit_fields(V& v, localization::CorrectedOdometryParams& p) {
  v.group("gicp", p.gicp);
  v("ground_band_m", p.ground_band_m);
  v("min_points", p.min_points);
  v("max_correction_step_m", p.max_correction_step_m);
  v("max_correction_step_rad", p.max_correction_step_rad);
  v("max_fitness_m2", p.max_fitness_m2);
  v("min_constraining_fraction", p.min_constraining_fraction);
}

// The top level: the navigator's own scalars first, then the components.
template <class V>
void visit_fields(V& v, FootstepNavigatorParams& p) {
  v("gicp_correction", p.gicp_correction);
  v("gicp_voxel_m", p.gicp_voxel_m);
  v("replan_deviation_m", p.replan_deviation_m);
  v("replan_deviation_rad", p.replan_deviation_rad);
  v("obstacle_margin_m", p.obstacle_margin_m);
  v("obstacle_step_m", p.obstacle_step_m);
  v("max_plans", p.max_plans);
  v("max_recovery_steps", p.max_recovery_steps);
  v.group("planner", p.planner);
  v.group("fusion", p.fusion);
  v.group("odometry", p.odometry);
}

// Reads the fields present in a mapping; finish() then rejects the keys no field asked for.
class ParamOverlay {
 public:
  explicit ParamOverlay(io::ParamReader& r) : r_(r) {}

  template <class T>
  void operator()(const char* key, T& value) {
    r_.get(key, value);
  }
  template <int N>
  void operator()(const char* key, Eigen::Matrix<double, N, 1>& value) {
    std::vector<double> xs;
    if (!r_.get(key, xs)) return;
    if (xs.size() != static_cast<std::size_t>(N)) r_.fail(key, "a list of " + std::to_string(N) + " numbers");
    for (int i = 0; i < N; ++i) value[i] = xs[static_cast<std::size_t>(i)];
  }
  template <class S>
  void group(const char* key, S& nested) {
    io::ParamReader child = r_.child(key);
    ParamOverlay overlay(child);
    visit_fields(overlay, nested);
    child.finish();
  }

 private:
  io::ParamReader& r_;
};

// The shortest text that reads back as the same double, with a ".0" on whole numbers so that the
// value is visibly a number of type double (YAML's .nan / .inf for non-finite values).
std::string double_text(double x) {
  if (std::isnan(x)) return ".nan";
  if (std::isinf(x)) return x > 0.0 ? ".inf" : "-.inf";
  char buf[64];
  const auto end = std::to_chars(buf, buf + sizeof buf, x).ptr;
  std::string s(buf, end);
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

class ParamDump {
 public:
  explicit ParamDump(YAML::Emitter& out) : out_(out) {}

  template <class T>
  void operator()(const char* key, const T& value) {
    out_ << YAML::Key << key << YAML::Value;
    if constexpr (std::is_floating_point_v<T>)
      out_ << double_text(value);
    else
      out_ << value;  // bool, integers, strings
  }
  template <int N>
  void operator()(const char* key, const Eigen::Matrix<double, N, 1>& value) {
    out_ << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (int i = 0; i < N; ++i) out_ << double_text(value[i]);
    out_ << YAML::EndSeq;
  }
  template <class S>
  void group(const char* key, S& nested) {
    out_ << YAML::Key << key << YAML::Value << YAML::BeginMap;
    visit_fields(*this, nested);
    out_ << YAML::EndMap;
  }

 private:
  YAML::Emitter& out_;
};

// The two top-level structs (NavigatorParams, FootstepNavigatorParams) are read and dumped alike.
template <class P>
void overlay_and_validate(io::ParamReader& r, P& p) {
  ParamOverlay overlay(r);
  visit_fields(overlay, p);
  r.finish();
  try {
    p.validate();
  } catch (const ParamError& e) {  // validate() names the field, not the file
    throw FileError(r.file(), "", e.what());
  }
}

template <class P>
void overlay_file(const std::filesystem::path& file, P& p) {
  io::ParamReader r = io::ParamReader::from_file(file);
  overlay_and_validate(r, p);
}

template <class P>
std::string dump_params_yaml(const P& p) {
  P fields = p;  // the visitors take non-const fields (the reader writes them)
  YAML::Emitter out;
  out << YAML::BeginMap;
  ParamDump dump(out);
  visit_fields(dump, fields);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace

void read_navigator_params(io::ParamReader& r, NavigatorParams& p) { overlay_and_validate(r, p); }
void read_navigator_params(io::ParamReader& r, FootstepNavigatorParams& p) { overlay_and_validate(r, p); }

void apply_navigator_params_file(const std::filesystem::path& file, NavigatorParams& p) { overlay_file(file, p); }
void apply_navigator_params_file(const std::filesystem::path& file, FootstepNavigatorParams& p) {
  overlay_file(file, p);
}

std::string navigator_params_yaml(const NavigatorParams& p) { return dump_params_yaml(p); }
std::string navigator_params_yaml(const FootstepNavigatorParams& p) { return dump_params_yaml(p); }

}  // namespace bipednav::navigation
