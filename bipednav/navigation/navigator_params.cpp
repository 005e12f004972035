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

// What derives from the robot's profile (its geometry, sensors and limits) rather than being tuned for
// it; the tuning is data (config/<robot>.params.yaml, read by navigator_params_for).

// The radius the robot's centre keeps from obstacles: its footprint plus its sideways sway.
double inscribed_radius_m(const RobotProfile& robot) { return robot.footprint_radius_m + robot.sway_amplitude_m; }

void set_costmaps(NavigatorParams& p, const RobotProfile& robot) {
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
  p.localization.max_odometry_speed_mps =
      2.0 * std::max(robot.limits.max_vel_x_mps, robot.limits.max_vel_x_backwards_mps);
  p.localization.max_odometry_rate_radps = 2.0 * robot.limits.max_vel_theta_radps;
}

// The local planners' (TEB, the path tracker) and the moving-obstacle yield's limits and radii.
void set_local_planner_limits(NavigatorParams& p, const RobotProfile& robot) {
  const double inscribed_m = inscribed_radius_m(robot);
  p.server.local.teb.limits.velocity = robot.limits;
  p.server.local.teb.limits.min_obstacle_dist_m = inscribed_m + 0.12;
  // TEB models how the body follows its commands (TebBodyResponse) where the profile's velocity lag
  // spans at least a control period (Digit's 0.3 s). A shorter lag is left to the acceleration limits:
  // the TurtleBot3's 0.05 s modelled cost it runs, hexagon_dynamic 2/5 against 5/5 on seeds 1-5
  // (bench/results/turtlebot3_tuning_seeds1-5_*.json).
  if (robot.tracking_time_constant_s >= 1.0 / p.control_rate_hz)
    p.server.local.teb.response.time_constant_s = robot.tracking_time_constant_s;
  p.server.local.tracker.limits = robot.limits;
  // Yielding to moving obstacles: the robot's inscribed radius (its swaying footprint).
  p.server.local.avoidance.robot_radius_m = inscribed_m;
}

void set_progress_window(NavigatorParams& p, const RobotProfile& robot) {
  // The progress window covers a full turn on the spot plus a short wait.
  p.server.progress.movement_time_allowance_s =
      std::max(p.server.progress.movement_time_allowance_s, 2.0 * 3.1416 / robot.limits.max_vel_theta_radps + 4.0);
}

}  // namespace

NavigatorParams NavigatorParams::for_robot(const RobotProfile& robot) {
  NavigatorParams p;
  set_costmaps(p, robot);
  set_obstacle_height(p, robot);
  set_odometry_jump_bounds(p, robot);
  set_local_planner_limits(p, robot);
  set_progress_window(p, robot);
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
