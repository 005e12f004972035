#pragma once

#include "bipednav/common/robot_profile.hpp"
#include "bipednav/common/twist.hpp"

namespace bipednav {

// Velocity and acceleration limits of a planar command (the walking controller's interface).
// max_vel_y_mps = 0 for forward/yaw-only robots (Digit's and a diff-drive's interface).
struct VelocityLimits {
  double max_vel_x_mps = 0.26;
  double max_vel_x_backwards_mps = 0.15;
  double max_vel_theta_radps = 1.0;
  double acc_lim_x_mps2 = 0.5;
  double acc_lim_theta_radps2 = 1.5;
  double max_vel_y_mps = 0.0;
  double acc_lim_y_mps2 = 0.5;

  void validate() const;
  // The limits of a robot profile (lateral motion disabled: the profiles are forward/yaw only).
  static VelocityLimits from_profile(const RobotProfile& robot);
  // The forward/yaw limits of any struct with the five fields of these names (a profile, TEB's and
  // the tracker's parameters); no lateral motion.
  template <class P>
  static VelocityLimits forward_yaw_of(const P& p) {
    VelocityLimits l;
    l.max_vel_x_mps = p.max_vel_x_mps;
    l.max_vel_x_backwards_mps = p.max_vel_x_backwards_mps;
    l.max_vel_theta_radps = p.max_vel_theta_radps;
    l.acc_lim_x_mps2 = p.acc_lim_x_mps2;
    l.acc_lim_theta_radps2 = p.acc_lim_theta_radps2;
    return l;
  }
};

// The one command limiter of the project (TEB, the tracker, the yield, the recoveries).
// Per axis: moves from `current` towards `desired` by at most acc_lim * dt_s, then clamps to the
// velocity limits (those win, so a robot measured above a limit is brought back under it at
// once). `current` is the measured velocity or the previous command; a non-finite component of
// either counts as 0, so a non-finite desired component brakes that axis at its acceleration
// limit. dt_s = 0 returns `current` clamped to the velocity limits. Throws Error for a negative
// or non-finite dt_s.
Twist limit_velocity(const Twist& desired, const Twist& current, double dt_s, const VelocityLimits& limits);

}  // namespace bipednav
