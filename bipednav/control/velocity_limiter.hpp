#pragma once

#include "bipednav/common/robot_profile.hpp"
#include "bipednav/common/twist.hpp"

namespace bipednav::control {

// Velocity and acceleration limits of the command sent to the walking controller.
// max_vel_y_mps = 0 for forward/yaw-only robots (Digit's and a diff-drive's interface).
struct VelocityLimits {
  double max_vel_x_mps = 0.26;
  double max_vel_x_backwards_mps = 0.15;
  double max_vel_y_mps = 0.0;
  double max_vel_theta_radps = 1.0;
  double acc_lim_x_mps2 = 0.5;
  double acc_lim_y_mps2 = 0.5;
  double acc_lim_theta_radps2 = 1.5;

  void validate() const;
  // The limits of a robot profile (lateral motion disabled: the profiles are forward/yaw only).
  static VelocityLimits from_profile(const RobotProfile& robot);
};

// Clamps `cmd` to the velocity limits, then moves from `previous` towards it by at most
// acc_lim * dt_s per axis (so limits hold whenever `previous` did). Non-finite components of
// `cmd` are replaced by 0 (the robot brakes at its acceleration limits); a non-finite
// `previous` component counts as 0. dt_s = 0 returns `previous` clamped to the velocity
// limits. Throws Error for a negative or non-finite dt_s.
Twist limit_velocity(const Twist& cmd, const Twist& previous, double dt_s, const VelocityLimits& limits);

// Stateful wrapper: remembers the last output and its time (simulated).
class VelocityLimiter {
 public:
  explicit VelocityLimiter(const VelocityLimits& limits);

  // Limits `cmd` issued at now_s against the previous output. The first call after
  // construction or reset() has no time step yet and returns the reset state (rest by default).
  Twist apply(const Twist& cmd, double now_s);
  // Forget the previous output (e.g. after the robot was stopped externally).
  void reset(const Twist& current = {}) {
    previous_ = current;
    has_previous_ = false;
  }
  const Twist& last() const { return previous_; }

 private:
  VelocityLimits limits_;
  Twist previous_;
  double previous_s_ = 0.0;
  bool has_previous_ = false;
};

}  // namespace bipednav::control
