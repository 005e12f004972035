#pragma once

#include "bipednav/common/twist.hpp"

namespace bipednav {

// Velocity and acceleration limits of a planar command (the walking controller's interface): a
// robot profile's (RobotProfile::limits), TEB's (TebLimits::velocity) and the path tracker's
// (TrackerParams::limits). max_vel_y_mps = 0 for forward/yaw-only robots (Digit's and a
// diff-drive's interface).
struct VelocityLimits {
  double max_vel_x_mps = 0.26;
  double max_vel_x_backwards_mps = 0.15;
  double max_vel_theta_radps = 1.0;
  double acc_lim_x_mps2 = 0.5;
  double acc_lim_theta_radps2 = 1.5;
  double max_vel_y_mps = 0.0;
  double acc_lim_y_mps2 = 0.5;

  void validate() const;

  // The fields of a robot profile or a navigation parameters file, read flat into the struct that
  // embeds the limits (no nested mapping). The lateral fields are left out: the profiles and the
  // local planners are forward/yaw only, so they keep max_vel_y_mps = 0.
  template <class V>
  void visit_fields(V& v) {
    v("max_vel_x_mps", max_vel_x_mps);
    v("max_vel_x_backwards_mps", max_vel_x_backwards_mps);
    v("max_vel_theta_radps", max_vel_theta_radps);
    v("acc_lim_x_mps2", acc_lim_x_mps2);
    v("acc_lim_theta_radps2", acc_lim_theta_radps2);
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
