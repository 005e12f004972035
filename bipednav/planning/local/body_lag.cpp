#include "bipednav/planning/local/body_lag.hpp"

#include <algorithm>
#include <cmath>

#include "bipednav/common/body_response.hpp"

namespace bipednav::planning::local {

Twist predict_body_velocity(const Twist& body, const Twist& cmd, double period_s, const BodyLag& lag) {
  const int steps = std::max(1, static_cast<int>(std::ceil(period_s / 0.01 - 1e-9)));
  const double h = period_s / steps;
  Twist v{body.linear_x, 0.0, body.angular_z};
  for (int i = 0; i < steps; ++i) v = track_command(v, cmd, h, lag.time_constant_s, lag.limits);
  return v;
}

Twist invert_body_lag(const Twist& body, const Twist& target, double horizon_s, const BodyLag& lag) {
  const VelocityLimits& l = lag.limits;
  // Fraction of a step change the lag covers within the horizon (1 without a lag).
  const double alpha =
      lag.time_constant_s > 0.0 && horizon_s > 0.0 ? 1.0 - std::exp(-horizon_s / lag.time_constant_s) : 1.0;
  Twist u;
  u.linear_x = std::clamp(body.linear_x + (target.linear_x - body.linear_x) / alpha, -l.max_vel_x_backwards_mps,
                          l.max_vel_x_mps);
  u.angular_z = std::clamp(body.angular_z + (target.angular_z - body.angular_z) / alpha, -l.max_vel_theta_radps,
                           l.max_vel_theta_radps);
  return u;
}

}  // namespace bipednav::planning::local
