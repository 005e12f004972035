#pragma once

// The field lists (navigator_params_yaml.cpp) of the footstep navigator's parameters
// (FootstepNavigatorParams): ARA* footsteps, the Kalman heightmap and GICP-corrected odometry.
#include "bipednav/navigation/footstep_navigator.hpp"

namespace bipednav::navigation::param_fields {

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

}  // namespace bipednav::navigation::param_fields
