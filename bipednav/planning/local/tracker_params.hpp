#pragma once

#include "bipednav/common/velocity_limits.hpp"

namespace bipednav::planning::local {

// Pure-pursuit style path tracker (the simple alternative to TEB).
struct TrackerParams {
  double lookahead_m = 0.6;
  // max_vel_x_backwards_mps only for yielding to moving obstacles and leaving inscribed space.
  VelocityLimits limits{.max_vel_x_mps = 0.5,
                        .max_vel_x_backwards_mps = 0.2,
                        .max_vel_theta_radps = 0.8,
                        .acc_lim_x_mps2 = 0.5,
                        .acc_lim_theta_radps2 = 1.0};
  double rotate_in_place_angle_rad = 0.8;  // turn on the spot when the lookahead point is further off
  double xy_goal_tolerance_m = 0.2;
  double yaw_goal_tolerance_rad = 0.2;
  // Once within xy_goal_tolerance_m, keep turning to the goal yaw until this far from the goal
  // (approach_goal's hysteresis); <= xy_goal_tolerance_m: none.
  double xy_goal_release_m = 0.0;
  double rotate_gain = 1.5;
  double control_period_s = 0.1;
  double collision_check_horizon_s = 1.0;  // forward-simulated arc checked against the costmap

  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v("lookahead_m", lookahead_m);
    limits.visit_fields(v);  // flat: the keys sit in tracker
    v("rotate_in_place_angle_rad", rotate_in_place_angle_rad);
    v("xy_goal_tolerance_m", xy_goal_tolerance_m);
    v("yaw_goal_tolerance_rad", yaw_goal_tolerance_rad);
    v("xy_goal_release_m", xy_goal_release_m);
    v("rotate_gain", rotate_gain);
    v("control_period_s", control_period_s);
    v("collision_check_horizon_s", collision_check_horizon_s);
  }
};

}  // namespace bipednav::planning::local
