#pragma once

#include "bipednav/common/twist.hpp"
#include "bipednav/common/velocity_limits.hpp"

namespace bipednav::planning::local {

// The body's velocity response to a held command, as the simulator models a walker
// (bipednav/common/body_response.hpp): per axis first-order tracking with time constant
// time_constant_s, each change bounded by the acceleration limit.
struct BodyLag {
  double time_constant_s = 0.0;  // 0: the body takes the command at once
  VelocityLimits limits;         // forward/yaw velocity and acceleration limits
};

// The body's forward and yaw velocity after holding cmd for period_s from body (first-order tracking
// in steps of at most 0.01 s, the simulator's step).
Twist predict_body_velocity(const Twist& body, const Twist& cmd, double period_s, const BodyLag& lag);

// The command that, held for horizon_s, brings a first-order lag from body to target: the lag's step
// response v(h) = v0 + (u - v0) (1 - exp(-h / tau)) solved for u, clamped to the velocity limits
// (forward and yaw; linear_y stays 0). With time_constant_s 0 the target itself.
Twist invert_body_lag(const Twist& body, const Twist& target, double horizon_s, const BodyLag& lag);

}  // namespace bipednav::planning::local
