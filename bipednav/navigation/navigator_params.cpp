#include <algorithm>
#include <cstdlib>

#include "bipednav/navigation/navigator.hpp"

#ifndef BIPEDNAV_CONFIG_DIR
#define BIPEDNAV_CONFIG_DIR "config"
#endif

namespace bipednav::navigation {

std::string config_dir() {
  const char* env = std::getenv("BIPEDNAV_CONFIG_DIR");
  return env && *env ? env : BIPEDNAV_CONFIG_DIR;
}

namespace {

// The radius the robot's centre keeps from obstacles: its footprint plus its sideways sway.
double inscribed_radius_m(const RobotProfile& robot) { return robot.footprint_radius_m + robot.sway_amplitude_m; }

void set_costmaps(NavigatorParams& p, const RobotProfile& robot) {
  p.local_map = mapping::LocalCostmapParams::for_robot(robot);
  p.global_map = mapping::GlobalCostmapParams::for_robot(robot);
  // A walker's base sways sideways while it steps: its centre needs that much more room, and a
  // gentler cost decay keeps paths in the middle of passages rather than along their edges.
  const double inscribed_m = inscribed_radius_m(robot);
  for (auto* m : {&p.local_map.inscribed_radius_m, &p.global_map.inscribed_radius_m}) *m = inscribed_m;
  for (auto* m : {&p.local_map.inflation_radius_m, &p.global_map.inflation_radius_m}) *m = inscribed_m + 0.45;
  for (auto* m : {&p.local_map.cost_scaling_factor, &p.global_map.cost_scaling_factor}) *m = 2.0;
}

void set_obstacle_height(NavigatorParams& p, const RobotProfile& robot) {
  // Obstacles count up to the top of the robot including its sensor mast (a TurtleBot carrying
  // Digit's sensors at Digit's heights is 0.2 m tall but its mast reaches 1.5 m).
  double top_m = robot.height_m;
  for (const auto& s : robot.sensors) top_m = std::max(top_m, s.z_m + 0.1);
  p.perception.obstacle_height_margin_m = top_m - robot.height_m;
}

void set_odometry_jump_bounds(NavigatorParams& p, const RobotProfile& robot) {
  // Odometry faster than twice the robot's limits has jumped.
  p.localization.max_odometry_speed_mps = 2.0 * std::max(robot.max_vel_x_mps, robot.max_vel_x_backwards_mps);
  p.localization.max_odometry_rate_radps = 2.0 * robot.max_vel_theta_radps;
}

// The settings screened on wheeled robots (kind diff_drive) only; walkers keep the defaults.
void set_diff_drive_settings(NavigatorParams& p) {
  // A wheeled robot's odometry follows its turns closely: LOAM projects the previous sweep with the
  // (checked) change of the odometry's rotation instead of constant velocity, which lags at turn
  // onsets. It is on together with the height-aware maps (mapping::height_aware_maps_for): with the maps
  // alone a fault run ended outside the goal's heading tolerance. Walkers keep constant velocity
  // (docs/closed-loop-log.md, 'Height-aware clearing and mark decay').
  p.localization.loam.reference_from_prior_change = true;
  // Wheeled robots also stop LOAM's correspondence rounds (odometry and mapping) at 1 mm / 3e-4 rad of
  // change instead of 0.1 mm / 1e-5 rad (~3 rounds per sweep instead of ~6; LoamParams keeps the tight
  // test) and factor TEB's Ceres solves with Eigen's sparse Cholesky instead of CHOLMOD (the same bands
  // to rounding; alone its CPU effect is within noise, it is here as half of the screened pair): less CPU
  // with no runs lost on the TurtleBot3; Digit lost runs with the LOAM setting, so walkers keep both off
  // (docs/closed-loop-log.md, 'TurtleBot3 CPU settings, and the switches left opt-in').
  for (auto* r : {&p.localization.loam.odometry.round_converged_translation_m,
                  &p.localization.loam.mapping.round_converged_translation_m})
    *r = 1e-3;
  for (auto* r : {&p.localization.loam.odometry.round_converged_rotation_rad,
                  &p.localization.loam.mapping.round_converged_rotation_rad})
    *r = 3e-4;
  p.server.local.teb.optim.ceres_sparse_library = "eigen_sparse";
  // Wheeled robots also run the "fast profile": TEB's banded Levenberg-Marquardt (the same
  // objective and trust-region schedule as Ceres, analytic Jacobians; bands equal to Ceres' to ~1e-11
  // m per solve), the newest depth frame per local map update (newest_depth_only) and RANSAC's models
  // from at most 4000 points: about a third less CPU, as robust as before on fresh seeds (docs/closed-loop-log.md,
  // 'Fresh-seed screens'). Walkers (the path tracker, not TEB) keep every frame and all RANSAC points.
  p.server.local.teb.optim.linear_solver = "banded_lm";
  p.newest_depth_only = true;
  p.perception.ransac.max_points = 4000;
  // Wheeled robots yield with held-then-braked candidates too (DynamicAvoidanceParams::hold_step_s):
  // stepping aside in a mover's lane between posts instead of standing in it, fewer box contacts.
  // Off for walkers: no gain for a lagging walker (docs/closed-loop-log.md, 'Held-then-braked yield candidates').
  p.server.local.avoidance.hold_step_s = 0.25;
}

// The local planners' (TEB, the path tracker) and the moving-obstacle yield's limits and radii.
void set_local_planner_limits(NavigatorParams& p, const RobotProfile& robot) {
  const double inscribed_m = inscribed_radius_m(robot);
  auto& lim = p.server.local.teb.limits;
  lim.max_vel_x_mps = robot.max_vel_x_mps;
  lim.max_vel_x_backwards_mps = robot.max_vel_x_backwards_mps;
  lim.max_vel_theta_radps = robot.max_vel_theta_radps;
  lim.acc_lim_x_mps2 = robot.acc_lim_x_mps2;
  lim.acc_lim_theta_radps2 = robot.acc_lim_theta_radps2;
  lim.min_obstacle_dist_m = inscribed_m + 0.12;
  // TEB models how the body follows its commands (TebBodyResponse) where the profile's velocity lag
  // spans at least a control period (Digit's 0.3 s). A shorter lag is left to the acceleration limits:
  // the TurtleBot3's 0.05 s modelled cost it runs, hexagon_dynamic 2/5 against 5/5 on seeds 1-5
  // (bench/results/turtlebot3_tuning_seeds1-5_*.json).
  if (robot.tracking_time_constant_s >= 1.0 / p.control_rate_hz)
    p.server.local.teb.response.time_constant_s = robot.tracking_time_constant_s;
  auto& tr = p.server.local.tracker;
  tr.max_vel_x_mps = robot.max_vel_x_mps;
  tr.max_vel_theta_radps = robot.max_vel_theta_radps;
  tr.acc_lim_x_mps2 = robot.acc_lim_x_mps2;
  tr.acc_lim_theta_radps2 = robot.acc_lim_theta_radps2;
  tr.max_vel_x_backwards_mps = robot.max_vel_x_backwards_mps;
  // Yielding to moving obstacles: the robot's inscribed radius (its swaying footprint).
  p.server.local.avoidance.robot_radius_m = inscribed_m;
}

void set_progress_window(NavigatorParams& p, const RobotProfile& robot) {
  // The progress window covers a full turn on the spot plus a short wait.
  p.server.progress.movement_time_allowance_s =
      std::max(p.server.progress.movement_time_allowance_s, 2.0 * 3.1416 / robot.max_vel_theta_radps + 4.0);
}

// The settings of walkers (kind walker), which follow their commands with a lag.
void set_walker_settings(NavigatorParams& p, const RobotProfile& robot) {
  // Walkers default to the path tracker (with its forward collision check): TEB with its model of the
  // walker's velocity lag (TebBodyResponse) succeeds as often over Digit's held-out seeds 11-30 (75/80
  // each) but one run less in three_rooms (15/20 against 16/20, cube contacts; README, closed-loop
  // results). `run --local-planner teb` overrides.
  if (robot.kind == "walker") p.server.local_planner = "tracker";
  // A walker brakes from its last command, not from its lagging odometry.
  p.brake_from_last_command = robot.kind == "walker";
  // A walker's 0.5 m-obstacle tracks keep their size while the blob shrinks under the LiDAR's lowest
  // ring, continue when found again, and a shrunken blob's centroid counts as noisier (both opt-ins
  // of MovingObstacleParams): fewer cube contacts for Digit in three_rooms. The TurtleBot3 keeps both
  // off: they cost it runs (docs/closed-loop-log.md, 'Known causes of failure, measured').
  if (robot.kind == "walker") p.moving_obstacles.radius_floor = p.moving_obstacles.partial_view_noise = true;
}

}  // namespace

NavigatorParams NavigatorParams::for_robot(const RobotProfile& robot) {
  NavigatorParams p;
  set_costmaps(p, robot);
  set_obstacle_height(p, robot);
  set_odometry_jump_bounds(p, robot);
  if (robot.kind == "diff_drive") set_diff_drive_settings(p);
  set_local_planner_limits(p, robot);
  set_progress_window(p, robot);
  set_walker_settings(p, robot);
  p.behavior_tree = config_dir() + "/behavior_trees/navigate.xml";
  return p;
}

void NavigatorParams::validate() const {
  perception.validate();
  localization.validate();
  local_map.validate();
  global_map.validate();
  server.validate();
  require(control_rate_hz > 0.0 && control_rate_hz <= 100.0, "control_rate_hz", "in (0, 100] Hz");
  sensors.validate();
  moving_obstacles.validate();
  require(!behavior_tree.empty(), "behavior_tree", "the path of a behavior tree XML file");
}

}  // namespace bipednav::navigation
