#include "bipednav/sim/robot_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "bipednav/common/error.hpp"

namespace bipednav::sim {

RobotModel::RobotModel(const RobotProfile& profile, const Pose2& start)
    : profile_(profile), walker_(profile.kind != "diff_drive"), nominal_(start), step_start_nominal_(start) {
  profile_.validate();
  if (!start.is_finite()) throw Error("RobotModel: non-finite start pose");
  state_.pose = start * sway_offset(0.0);
  state_.velocity.linear_y = sway_rate_mps(0.0);
}

Pose2 RobotModel::sway_offset(double t_s) const {
  if (!walker_ || profile_.sway_amplitude_m <= 0.0) return {};
  return {0.0, profile_.sway_amplitude_m * std::sin(std::numbers::pi * profile_.step_frequency_hz * t_s), 0.0};
}

double RobotModel::sway_rate_mps(double t_s) const {
  if (!walker_ || profile_.sway_amplitude_m <= 0.0) return 0.0;
  const double k = std::numbers::pi * profile_.step_frequency_hz;
  return profile_.sway_amplitude_m * k * std::cos(k * t_s);
}

const RobotState& RobotModel::step(const Twist& cmd, double dt_s) {
  if (!cmd.is_finite()) throw Error("RobotModel::step: non-finite velocity command");
  if (!(dt_s > 0.0) || !std::isfinite(dt_s)) throw Error("RobotModel::step: dt must be > 0");
  const double v_target =
      std::clamp(cmd.linear_x, -profile_.limits.max_vel_x_backwards_mps, profile_.limits.max_vel_x_mps);
  const double w_target =
      std::clamp(cmd.angular_z, -profile_.limits.max_vel_theta_radps, profile_.limits.max_vel_theta_radps);
  v_ = track_first_order(v_, v_target, dt_s, profile_.tracking_time_constant_s, profile_.limits.acc_lim_x_mps2 * dt_s);
  w_ = track_first_order(w_, w_target, dt_s, profile_.tracking_time_constant_s,
                         profile_.limits.acc_lim_theta_radps2 * dt_s);

  step_start_s_ = time_s_;
  step_start_nominal_ = nominal_;
  nominal_ = integrate_arc(nominal_, v_, w_, dt_s);
  time_s_ += dt_s;
  state_.pose = nominal_ * sway_offset(time_s_);
  state_.velocity = Twist{v_, sway_rate_mps(time_s_), w_};
  return state_;
}

Pose2 RobotModel::pose_in_last_step(double tau_s) const {
  const Pose2 nominal = integrate_arc(step_start_nominal_, v_, w_, tau_s);
  return nominal * sway_offset(step_start_s_ + tau_s);
}

}  // namespace bipednav::sim
