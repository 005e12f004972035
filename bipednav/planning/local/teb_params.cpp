#include "bipednav/planning/local/teb_params.hpp"

#include <cmath>

#include "bipednav/common/error.hpp"

namespace bipednav::planning::local {

namespace {
bool pos(double v) { return std::isfinite(v) && v > 0.0; }
bool nonneg(double v) { return std::isfinite(v) && v >= 0.0; }
}  // namespace

void TebLimits::validate() const {
  velocity.validate();
  require(nonneg(min_obstacle_dist_m), "min_obstacle_dist_m", ">= 0");
}

void TebBandParams::validate() const {
  require(pos(dt_ref_s), "dt_ref_s", "> 0");
  require(std::isfinite(dt_hysteresis_s) && dt_hysteresis_s >= dt_ref_s / 3.0 - 1e-12 && dt_hysteresis_s < dt_ref_s,
          "dt_hysteresis_s", "in [dt_ref_s / 3, dt_ref_s) (smaller values let the pose count oscillate)");
  require(min_samples >= 2, "min_samples", ">= 2");
  require(max_samples > min_samples, "max_samples", "> min_samples");
  require(pos(dt_min_s) && dt_min_s < dt_ref_s, "dt_min_s", "in (0, dt_ref_s)");
  require(pos(reinit_goal_dist_m), "reinit_goal_dist_m", "> 0");
  require(pos(reinit_goal_angle_rad), "reinit_goal_angle_rad", "> 0");
}

void TebOptimizerParams::validate() const {
  for (double w : {weight_optimaltime, weight_kinematics_nh, weight_backwards, weight_max_vel_x, weight_max_vel_theta,
                   weight_acc_lim_x, weight_acc_lim_theta, weight_obstacle, weight_viapoint, weight_dynamic_obstacle})
    require(nonneg(w), "weight_*", "finite weights >= 0");
  require(std::isfinite(weight_adapt_factor) && weight_adapt_factor >= 1.0, "weight_adapt_factor", ">= 1");
  require(nonneg(penalty_epsilon), "penalty_epsilon", ">= 0");
  require(pos(sign_gain), "sign_gain", "> 0");
  require(pos(function_tolerance) && function_tolerance < 1.0, "function_tolerance", "in (0, 1)");
  require(no_inner_iterations >= 1, "no_inner_iterations", ">= 1");
  require(no_outer_iterations >= 1, "no_outer_iterations", ">= 1");
  require(obstacles_per_pose >= 0 && obstacles_per_pose <= 8, "obstacles_per_pose", "in [0, 8]");
  require(pos(obstacle_influence_dist_m), "obstacle_influence_dist_m", "> 0");
  require(nonneg(dynamic_obstacle_dist_m), "dynamic_obstacle_dist_m", ">= 0");
  require(nonneg(dynamic_obstacle_max_prediction_s), "dynamic_obstacle_max_prediction_s", ">= 0");
  require(nonneg(dynamic_obstacle_growth_mps), "dynamic_obstacle_growth_mps", ">= 0");
  require(nonneg(dynamic_obstacle_lead_s), "dynamic_obstacle_lead_s", ">= 0");
  require(linear_solver == "banded_lm" || linear_solver == "sparse_normal_cholesky" ||
              linear_solver == "dense_normal_cholesky" || linear_solver == "dense_qr" || linear_solver == "dense_schur",
          "linear_solver", "banded_lm, sparse_normal_cholesky, dense_normal_cholesky, dense_qr or dense_schur");
  require(ceres_sparse_library == "suite_sparse" || ceres_sparse_library == "eigen_sparse", "ceres_sparse_library",
          "suite_sparse or eigen_sparse");
}

void ObstacleParams::validate() const {
  require(nonneg(point_max_extent_m), "point_max_extent_m", ">= 0");
  require(nonneg(line_max_width_m), "line_max_width_m", ">= 0");
  require(pos(cluster_block_m), "cluster_block_m", "> 0");
  require(max_obstacles >= 0, "max_obstacles", ">= 0");
}

void HomotopyParams::validate() const {
  require(max_classes >= 1, "max_classes", ">= 1");
  require(num_threads >= 1, "num_threads", ">= 1");
  require(pos(selection_hysteresis) && selection_hysteresis <= 1.0, "selection_hysteresis", "in (0, 1]");
  require(nonneg(corridor_halfwidth_m), "corridor_halfwidth_m", ">= 0");
  require(max_keypoint_obstacles >= 0, "max_keypoint_obstacles", ">= 0");
  require(nonneg(keypoint_margin_m), "keypoint_margin_m", ">= 0");
  require(max_path_expansions >= 1, "max_path_expansions", ">= 1");
  require(pos(signature_tolerance_rad), "signature_tolerance_rad", "> 0");
  require(pos(roadmap_clearance_ratio) && roadmap_clearance_ratio <= 1.0, "roadmap_clearance_ratio", "in (0, 1]");
  require(std::isfinite(max_cost_ratio) && max_cost_ratio >= 1.0, "max_cost_ratio", ">= 1");
}

void TebBodyResponse::validate() const {
  require(nonneg(time_constant_s), "time_constant_s", ">= 0 s");
  require(nonneg(horizon_s), "horizon_s", ">= 0 s (0: one control period)");
}

void TebParams::validate() const {
  limits.validate();
  band.validate();
  optim.validate();
  obstacles.validate();
  homotopy.validate();
  response.validate();
  require(pos(lookahead_m), "lookahead_m", "> 0");
  require(nonneg(window_margin_m), "window_margin_m", ">= 0");
  require(pos(via_point_separation_m), "via_point_separation_m", "> 0");
  require(pos(xy_goal_tolerance_m), "xy_goal_tolerance_m", "> 0");
  require(pos(yaw_goal_tolerance_rad), "yaw_goal_tolerance_rad", "> 0");
  require(std::isfinite(xy_goal_release_m) && xy_goal_release_m >= 0.0, "xy_goal_release_m", ">= 0");
  require(pos(rotate_gain), "rotate_gain", "> 0");
  require(pos(control_period_s), "control_period_s", "> 0");
  require(feasibility_check_poses >= 1, "feasibility_check_poses", ">= 1");
  require(oscillation_window >= 4, "oscillation_window", ">= 4");
}

}  // namespace bipednav::planning::local
