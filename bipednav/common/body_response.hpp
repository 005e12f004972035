#pragma once

#include <algorithm>
#include <cmath>

#include "bipednav/common/pose2.hpp"

namespace bipednav {

// The body's response to a velocity command, shared by the simulator (sim::RobotModel) and the
// collision monitor (control::CollisionMonitor), so that the monitor predicts the body with the
// simulator's model: per step, each axis follows the command by first-order tracking, then the
// pose follows the arc of the new velocities.

// One step of first-order tracking toward target with time constant time_constant_s (0: at once),
// each change limited to max_delta (the acceleration limit times dt_s).
inline double track_first_order(double current, double target, double dt_s, double time_constant_s, double max_delta) {
  const double alpha = time_constant_s > 0.0 ? 1.0 - std::exp(-dt_s / time_constant_s) : 1.0;
  return current + std::clamp((target - current) * alpha, -max_delta, max_delta);
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
