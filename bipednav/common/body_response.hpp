#pragma once

#include <algorithm>
#include <cmath>

#include "bipednav/common/pose2.hpp"
#include "bipednav/common/twist.hpp"
#include "bipednav/common/velocity_limits.hpp"

namespace bipednav {

// The body's response to a velocity command, shared by the simulator (sim::RobotModel), the
// collision monitor (control::CollisionMonitor) and TEB's lag model (planning/local/body_lag), so
// that both predict the body with the simulator's model: per step, each axis follows the command by
// first-order tracking, then the pose follows the arc of the new velocities.

// One step of first-order tracking toward target with time constant time_constant_s (0: at once),
// each change limited to max_delta (the acceleration limit times dt_s).
inline double track_first_order(double current, double target, double dt_s, double time_constant_s, double max_delta) {
  const double alpha = time_constant_s > 0.0 ? 1.0 - std::exp(-dt_s / time_constant_s) : 1.0;
  return current + std::clamp((target - current) * alpha, -max_delta, max_delta);
}

// One step of the body's velocity toward a command: the command clamped to the velocity limits, then
// each axis tracked (track_first_order) within its acceleration limit. The lateral axis moves only
// where the limits allow lateral motion (max_vel_y_mps > 0); otherwise it keeps its value.
inline Twist track_command(const Twist& velocity, const Twist& cmd, double dt_s, double time_constant_s,
                           const VelocityLimits& lim) {
  const double tx = std::clamp(cmd.linear_x, -lim.max_vel_x_backwards_mps, lim.max_vel_x_mps);
  const double tw = std::clamp(cmd.angular_z, -lim.max_vel_theta_radps, lim.max_vel_theta_radps);
  Twist v = velocity;
  v.linear_x = track_first_order(v.linear_x, tx, dt_s, time_constant_s, lim.acc_lim_x_mps2 * dt_s);
  if (lim.max_vel_y_mps > 0.0) {
    const double ty = std::clamp(cmd.linear_y, -lim.max_vel_y_mps, lim.max_vel_y_mps);
    v.linear_y = track_first_order(v.linear_y, ty, dt_s, time_constant_s, lim.acc_lim_y_mps2 * dt_s);
  }
  v.angular_z = track_first_order(v.angular_z, tw, dt_s, time_constant_s, lim.acc_lim_theta_radps2 * dt_s);
  return v;
}

// Pose after driving at constant (v, w) for t seconds along an arc (exact unicycle motion).
inline Pose2 integrate_arc(const Pose2& start, double v_mps, double w_radps, double t_s) {
  const double dth = w_radps * t_s;
  double fx, fy;  // displacement in the start frame
  if (std::abs(dth) < 1e-9) {
    fx = v_mps * t_s;
    fy = 0.5 * v_mps * t_s * dth;
  } else {
    const double r = v_mps / w_radps;
    fx = r * std::sin(dth);
    fy = r * (1.0 - std::cos(dth));
  }
  return start * Pose2{fx, fy, dth};
}

}  // namespace bipednav
