#include "bipednav/control/velocity_limiter.hpp"

#include <algorithm>
#include <cmath>

#include "bipednav/common/error.hpp"

namespace bipednav::control {
namespace {

double finite_or_zero(double v) { return std::isfinite(v) ? v : 0.0; }

// One axis: clamp the target to [lo, hi], then step from `prev` by at most max_step.
double limit_axis(double target, double prev, double lo, double hi, double max_step) {
  const double t = std::clamp(finite_or_zero(target), lo, hi);
  const double p = std::clamp(finite_or_zero(prev), lo, hi);
  return std::clamp(t, p - max_step, p + max_step);
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

VelocityLimits VelocityLimits::from_profile(const RobotProfile& robot) {
  VelocityLimits l;
  l.max_vel_x_mps = robot.max_vel_x_mps;
  l.max_vel_x_backwards_mps = robot.max_vel_x_backwards_mps;
  l.max_vel_y_mps = 0.0;
  l.max_vel_theta_radps = robot.max_vel_theta_radps;
  l.acc_lim_x_mps2 = robot.acc_lim_x_mps2;
  l.acc_lim_theta_radps2 = robot.acc_lim_theta_radps2;
  l.validate();
  return l;
}

Twist limit_velocity(const Twist& cmd, const Twist& previous, double dt_s, const VelocityLimits& lim) {
  if (!std::isfinite(dt_s) || dt_s < 0.0) throw Error("limit_velocity: dt_s must be finite and >= 0");
  Twist out;
  out.linear_x = limit_axis(cmd.linear_x, previous.linear_x, -lim.max_vel_x_backwards_mps, lim.max_vel_x_mps,
                            lim.acc_lim_x_mps2 * dt_s);
  out.linear_y =
      limit_axis(cmd.linear_y, previous.linear_y, -lim.max_vel_y_mps, lim.max_vel_y_mps, lim.acc_lim_y_mps2 * dt_s);
  out.angular_z = limit_axis(cmd.angular_z, previous.angular_z, -lim.max_vel_theta_radps, lim.max_vel_theta_radps,
                             lim.acc_lim_theta_radps2 * dt_s);
  return out;
}

VelocityLimiter::VelocityLimiter(const VelocityLimits& limits) : limits_(limits) { limits_.validate(); }

Twist VelocityLimiter::apply(const Twist& cmd, double now_s) {
  if (!std::isfinite(now_s)) throw Error("VelocityLimiter::apply: time is not finite");
  if (has_previous_ && now_s < previous_s_) throw Error("VelocityLimiter::apply: time went backwards");
  const double dt = has_previous_ ? now_s - previous_s_ : 0.0;
  previous_ = limit_velocity(cmd, previous_, dt, limits_);
  previous_s_ = now_s;
  has_previous_ = true;
  return previous_;
}

}  // namespace bipednav::control
