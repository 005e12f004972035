#include "bipednav/common/velocity_limits.hpp"

#include <algorithm>
#include <cmath>

#include "bipednav/common/error.hpp"

namespace bipednav {
namespace {

double finite_or_zero(double v) { return std::isfinite(v) ? v : 0.0; }

// One axis: step from `current` towards `desired` by at most max_step, then clamp to [lo, hi].
double limit_axis(double desired, double current, double lo, double hi, double max_step) {
  const double c = finite_or_zero(current);
  return std::clamp(std::clamp(finite_or_zero(desired), c - max_step, c + max_step), lo, hi);
}

}  // namespace

void VelocityLimits::validate() const {
  const auto nonneg = [](double v) { return std::isfinite(v) && v >= 0.0; };
  const auto pos = [](double v) { return std::isfinite(v) && v > 0.0; };
  require(pos(max_vel_x_mps), "max_vel_x_mps", "> 0 m/s");
  require(nonneg(max_vel_x_backwards_mps), "max_vel_x_backwards_mps", ">= 0 m/s");
  require(nonneg(max_vel_y_mps), "max_vel_y_mps", ">= 0 m/s (0 for forward/yaw-only robots)");
  require(pos(max_vel_theta_radps), "max_vel_theta_radps", "> 0 rad/s");
  require(pos(acc_lim_x_mps2), "acc_lim_x_mps2", "> 0 m/s^2");
  require(pos(acc_lim_y_mps2), "acc_lim_y_mps2", "> 0 m/s^2");
  require(pos(acc_lim_theta_radps2), "acc_lim_theta_radps2", "> 0 rad/s^2");
}

Twist limit_velocity(const Twist& desired, const Twist& current, double dt_s, const VelocityLimits& lim) {
  if (!std::isfinite(dt_s) || dt_s < 0.0) throw Error("limit_velocity: dt_s must be finite and >= 0");
  Twist out;
  out.linear_x = limit_axis(desired.linear_x, current.linear_x, -lim.max_vel_x_backwards_mps, lim.max_vel_x_mps,
                            lim.acc_lim_x_mps2 * dt_s);
  if (lim.max_vel_y_mps > 0.0)  // else 0 (forward/yaw-only robot)
    out.linear_y = limit_axis(desired.linear_y, current.linear_y, -lim.max_vel_y_mps, lim.max_vel_y_mps,
                              lim.acc_lim_y_mps2 * dt_s);
  out.angular_z = limit_axis(desired.angular_z, current.angular_z, -lim.max_vel_theta_radps, lim.max_vel_theta_radps,
                             lim.acc_lim_theta_radps2 * dt_s);
  return out;
}

}  // namespace bipednav
