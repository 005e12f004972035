#pragma once

#include <string>

#include "bipednav/common/velocity_limits.hpp"

namespace bipednav::planning::local {

// Kinematic limits of a walking robot modelled as a differential drive (thesis 5.2): forward
// speed and yaw rate only, no lateral velocity; backwards walking allowed but slower and penalised.
struct TebLimits {
  VelocityLimits velocity{.max_vel_x_mps = 0.5,
                          .max_vel_x_backwards_mps = 0.2,
                          .max_vel_theta_radps = 0.8,
                          .acc_lim_x_mps2 = 0.5,
                          .acc_lim_theta_radps2 = 1.0};
  double min_obstacle_dist_m = 0.35;  // rho_min of eq. 5.15, from the robot centre

  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    velocity.visit_fields(v);  // flat: the keys sit in limits
    v("min_obstacle_dist_m", min_obstacle_dist_m);
  }
};

// The band's temporal resolution and its re-sampling hysteresis.
struct TebBandParams {
  double dt_ref_s = 0.3;
  double dt_hysteresis_s = 0.1;
  int min_samples = 3;
  int max_samples = 100;
  double dt_min_s = 0.01;               // lower bound of every dT_k
  double reinit_goal_dist_m = 1.0;      // re-initialise the band when the local goal jumps further
  double reinit_goal_angle_rad = 1.57;  // ... or turns further

  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v("dt_ref_s", dt_ref_s);
    v("dt_hysteresis_s", dt_hysteresis_s);
    v("min_samples", min_samples);
    v("max_samples", max_samples);
    v("dt_min_s", dt_min_s);
    v("reinit_goal_dist_m", reinit_goal_dist_m);
    v("reinit_goal_angle_rad", reinit_goal_angle_rad);
  }
};

// Weights of the quadratic penalties (eq. 5.16-5.21) and the solver schedule.
struct TebOptimizerParams {
  double weight_optimaltime = 1.0;       // dT^2, eq. 5.4
  double weight_kinematics_nh = 1000.0;  // eq. 5.16
  double weight_backwards = 2.0;         // walking backwards is allowed but costs extra
  double weight_max_vel_x = 2.0;         // eq. 5.13
  double weight_max_vel_theta = 1.0;
  double weight_acc_lim_x = 1.0;  // eq. 5.14
  double weight_acc_lim_theta = 1.0;
  double weight_obstacle = 50.0;  // eq. 5.19
  double weight_viapoint = 1.0;
  double weight_adapt_factor = 2.0;  // obstacle/kinematics weights grow by this per outer iteration
  double penalty_epsilon = 0.05;     // epsilon margin of the inequality penalties
  double sign_gain = 100.0;          // gamma of the smooth sign approximation, eq. 5.10
  int no_inner_iterations = 5;       // Levenberg-Marquardt iterations per solve
  int no_outer_iterations = 2;       // solves, with weight adaptation in between
  double function_tolerance = 1e-4;  // relative cost change ending a solve early (warm starts converge fast)
  int obstacles_per_pose = 2;        // nearest obstacles entering the problem per pose
  double obstacle_influence_dist_m = 1.5;
  // "banded_lm": the dedicated Levenberg-Marquardt of teb_lm (analytic Jacobians, band Cholesky of the
  // normal equations); or Ceres' Levenberg-Marquardt with automatic Jacobians and the linear solver
  // "sparse_normal_cholesky" (SuiteSparse), "dense_normal_cholesky", "dense_qr" or "dense_schur". All
  // minimise the same objective with the same trust-region schedule; banded_lm follows Ceres to rounding, so
  // the closed loops' differences between the solvers are chance. Ceres is the struct's default; the TurtleBot3
  // runs banded_lm for its lower CPU (config/turtlebot3.params.yaml; evidence in docs/closed-loop-log.md).
  // Moving obstacles in the band (teb_local_planner's include_dynamic_obstacles / EdgeDynamicObstacle):
  // for every inner pose s_i and every moving track j (LocalPlanner's tracker, MovingObstacleTracker::moving)
  // the residual sqrt(weight_dynamic_obstacle) * max{0, (r_robot + r_j + dynamic_obstacle_dist_m + eps) -
  // |s_i - c_j(t_i)|}, c_j the track's constant-velocity prediction at the pose's time t_i (the sum of the
  // band's dT up to i, taken when each solve is set up and held fixed during it, at most
  // dynamic_obstacle_max_prediction_s), r_robot the avoidance robot radius (DynamicAvoidanceParams). Its
  // weight is adapted with the static obstacle weight. The tracks' cells stay in the static obstacles too
  // (as teb_local_planner, which keeps costmap obstacles and dynamic obstacles apart): the costmap still
  // holds them, the feasibility check and the homotopy roadmap see them, and at t = 0 the static copy is
  // where the track is. The yield step still runs afterwards.
  // Off by default: on against off it scored within the closed loops' noise and made a pair worse, also
  // with the bound below (docs/closed-loop-log.md, 'Moving obstacles: tracking, yielding, ...').
  // The bound grows by dynamic_obstacle_growth_mps per second of prediction (as
  // DynamicAvoidanceParams::prediction_growth_mps: a constant-velocity prediction misses turns) and uses the
  // track's largest blob radius (dynamic_obstacle_largest_radius: TrackedObstacle::max_radius_m; a half-seen
  // obstacle's track shrinks to its visible face); dynamic_obstacle_lead_s > 0 keeps the bound from the
  // segment the obstacle sweeps over the next lead_s (a band passing in front of it then keeps the bound from
  // where it will be; 0 because a 1.0 s lead lost runs). All three act only with dynamic_obstacles.
  bool dynamic_obstacles = false;
  double weight_dynamic_obstacle = 50.0;
  double dynamic_obstacle_dist_m = 0.12;  // margin beyond robot radius + track radius
  double dynamic_obstacle_max_prediction_s = 4.0;
  double dynamic_obstacle_growth_mps = 0.05;    // the bound grows this much per second of prediction
  double dynamic_obstacle_lead_s = 0.0;         // > 0: the bound from the segment swept over the next lead_s
  bool dynamic_obstacle_largest_radius = true;  // the track's largest blob radius, not its latest
  std::string linear_solver = "sparse_normal_cholesky";
  // Ceres-only solver setting (the Ceres linear solvers above; banded_lm ignores it): sparse_normal_cholesky's
  // factorisation, "suite_sparse" (CHOLMOD, Ceres' own default) or "eigen_sparse" (Eigen's simplicial LDLT: the
  // same bands to rounding, less set-up per solve). The TurtleBot3 uses eigen_sparse (config/turtlebot3.params.yaml).
  std::string ceres_sparse_library = "suite_sparse";

  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v("weight_optimaltime", weight_optimaltime);
    v("weight_kinematics_nh", weight_kinematics_nh);
    v("weight_backwards", weight_backwards);
    v("weight_max_vel_x", weight_max_vel_x);
    v("weight_max_vel_theta", weight_max_vel_theta);
    v("weight_acc_lim_x", weight_acc_lim_x);
    v("weight_acc_lim_theta", weight_acc_lim_theta);
    v("weight_obstacle", weight_obstacle);
    v("weight_viapoint", weight_viapoint);
    v("weight_adapt_factor", weight_adapt_factor);
    v("penalty_epsilon", penalty_epsilon);
    v("sign_gain", sign_gain);
    v("no_inner_iterations", no_inner_iterations);
    v("no_outer_iterations", no_outer_iterations);
    v("function_tolerance", function_tolerance);
    v("obstacles_per_pose", obstacles_per_pose);
    v("obstacle_influence_dist_m", obstacle_influence_dist_m);
    v("dynamic_obstacles", dynamic_obstacles);
    v("weight_dynamic_obstacle", weight_dynamic_obstacle);
    v("dynamic_obstacle_dist_m", dynamic_obstacle_dist_m);
    v("dynamic_obstacle_max_prediction_s", dynamic_obstacle_max_prediction_s);
    v("dynamic_obstacle_growth_mps", dynamic_obstacle_growth_mps);
    v("dynamic_obstacle_lead_s", dynamic_obstacle_lead_s);
    v("dynamic_obstacle_largest_radius", dynamic_obstacle_largest_radius);
    v("linear_solver", linear_solver);
    v("ceres_sparse_library", ceres_sparse_library);
  }
};

// Converting lethal costmap cells into point, line and polygon obstacles.
struct ObstacleParams {
  double point_max_extent_m = 0.15;  // clusters smaller than this become a point
  double line_max_width_m = 0.12;    // elongated clusters thinner than this become a segment
  double cluster_block_m = 1.0;      // large clusters are cut into blocks so hulls stay local
  int max_obstacles = 400;

  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v("point_max_extent_m", point_max_extent_m);
    v("line_max_width_m", line_max_width_m);
    v("cluster_block_m", cluster_block_m);
    v("max_obstacles", max_obstacles);
  }
};

// Topologically distinct candidate trajectories (homotopy classes), optimised in parallel.
struct HomotopyParams {
  bool enabled = true;
  int max_classes = 3;
  int num_threads = 1;
  double selection_hysteresis = 0.9;  // the selected class's cost is scaled by this when comparing
  double corridor_halfwidth_m = 2.0;  // obstacles further off the start-goal line get no keypoints
  int max_keypoint_obstacles = 6;
  double keypoint_margin_m = 0.1;
  int max_path_expansions = 500;
  double roadmap_clearance_ratio = 0.5;  // roadmap edges keep this fraction of min_obstacle_dist (as TEB)
  double max_cost_ratio = 2.5;           // unselected bands costing more than this times the best are dropped
  double signature_tolerance_rad = 1.0;

  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v("enabled", enabled);
    v("max_classes", max_classes);
    v("num_threads", num_threads);
    v("selection_hysteresis", selection_hysteresis);
    v("corridor_halfwidth_m", corridor_halfwidth_m);
    v("max_keypoint_obstacles", max_keypoint_obstacles);
    v("keypoint_margin_m", keypoint_margin_m);
    v("max_path_expansions", max_path_expansions);
    v("roadmap_clearance_ratio", roadmap_clearance_ratio);
    v("max_cost_ratio", max_cost_ratio);
    v("signature_tolerance_rad", signature_tolerance_rad);
  }
};

// How the body follows a velocity command (a walker's walking controller: the profile's
// tracking_time_constant_s, derived in NavigatorParams::for_robot). With time_constant_s > 0 the planner models a
// first-order lag between command and body velocity: the band starts from the body's velocity (where the
// navigator passes its braking reference, the lag's prediction from the previous command) and the command
// sent is the one that brings the lagging body to the band's first-interval velocity within horizon_s
// (invert_body_lag), instead of that velocity itself, which a lagging body reaches only after several
// cycles. docs/architecture.md (4. Local planning, 'Body response') gives the measurements behind this form.
struct TebBodyResponse {
  double time_constant_s = 0.0;  // 0: the body takes the command at once (no lag model)
  double horizon_s = 0.0;        // 0: one control period

  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v("time_constant_s", time_constant_s);
    v("horizon_s", horizon_s);
  }
};

// The whole TEB planner.
struct TebParams {
  TebLimits limits;
  TebBandParams band;
  TebOptimizerParams optim;
  ObstacleParams obstacles;
  HomotopyParams homotopy;
  TebBodyResponse response;
  double lookahead_m = 3.0;      // local goal: at most this far along the global path
  double window_margin_m = 0.2;  // ... and this far inside the local costmap border
  double via_point_separation_m = 0.5;
  double xy_goal_tolerance_m = 0.2;
  double yaw_goal_tolerance_rad = 0.2;
  // Once within xy_goal_tolerance_m, keep turning to the goal yaw until this far from the goal
  // (approach_goal's hysteresis); <= xy_goal_tolerance_m: none.
  double xy_goal_release_m = 0.0;
  double rotate_gain = 1.5;  // yaw-rate per rad of yaw error when turning on the goal
  double control_period_s = 0.1;
  int feasibility_check_poses = 5;
  int oscillation_window = 20;  // commands in the oscillation detector's buffer

  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v.group("limits", limits);
    v.group("band", band);
    v.group("optim", optim);
    v.group("obstacles", obstacles);
    v.group("homotopy", homotopy);
    v.group("response", response);
    v("lookahead_m", lookahead_m);
    v("window_margin_m", window_margin_m);
    v("via_point_separation_m", via_point_separation_m);
    v("xy_goal_tolerance_m", xy_goal_tolerance_m);
    v("yaw_goal_tolerance_rad", yaw_goal_tolerance_rad);
    v("xy_goal_release_m", xy_goal_release_m);
    v("rotate_gain", rotate_gain);
    v("control_period_s", control_period_s);
    v("feasibility_check_poses", feasibility_check_poses);
    v("oscillation_window", oscillation_window);
  }
};

}  // namespace bipednav::planning::local
