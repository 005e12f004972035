#include "bipednav/sim/odometry_model.hpp"

#include <cmath>

#include "bipednav/common/error.hpp"

namespace bipednav::sim {

void OdometryParams::validate() const {
  require(rate_hz > 0 && std::isfinite(rate_hz), "rate_hz", "> 0");
  require(std::abs(linear_scale_error) < 0.5, "linear_scale_error", "in (-0.5, 0.5)");
  require(std::abs(angular_scale_error) < 0.5, "angular_scale_error", "in (-0.5, 0.5)");
  require(std::isfinite(yaw_bias_radps) && std::abs(yaw_bias_radps) < 1.0, "yaw_bias_radps",
          "finite, |bias| < 1 rad/s");
  require(linear_random_walk_m_per_sqrt_s >= 0 && std::isfinite(linear_random_walk_m_per_sqrt_s),
          "linear_random_walk_m_per_sqrt_s", ">= 0");
  require(yaw_random_walk_rad_per_sqrt_s >= 0 && std::isfinite(yaw_random_walk_rad_per_sqrt_s),
          "yaw_random_walk_rad_per_sqrt_s", ">= 0");
  require(imu_tilt_noise_rad >= 0 && std::isfinite(imu_tilt_noise_rad), "imu_tilt_noise_rad", ">= 0");
}

OdometryModel::OdometryModel(const OdometryParams& params, std::uint64_t seed) : params_(params), rng_(seed) {
  params_.validate();
}

void OdometryModel::integrate(const Twist& v, double dt_s) {
  if (!(dt_s > 0.0)) return;
  // White velocity noise of density q gives a position random walk q * sqrt(t).
  const double inv_sqrt_dt = 1.0 / std::sqrt(dt_s);
  const double sl = params_.linear_random_walk_m_per_sqrt_s * inv_sqrt_dt;
  const double sw = params_.yaw_random_walk_rad_per_sqrt_s * inv_sqrt_dt;
  velocity_.linear_x = v.linear_x * (1.0 + params_.linear_scale_error) + rng_.normal(0.0, sl);
  velocity_.linear_y = v.linear_y * (1.0 + params_.linear_scale_error) + rng_.normal(0.0, sl);
  velocity_.angular_z =
      v.angular_z * (1.0 + params_.angular_scale_error) + params_.yaw_bias_radps + rng_.normal(0.0, sw);
  // Midpoint rule on the heading keeps arcs accurate at 100 Hz.
  const double half = 0.5 * velocity_.angular_z * dt_s;
  const Pose2 mid{0.0, 0.0, half};
  const Eigen::Vector2d d = mid.transform({velocity_.linear_x * dt_s, velocity_.linear_y * dt_s});
  pose_ = pose_ * Pose2{d.x(), d.y(), 2.0 * half};
}

Odometry OdometryModel::measure(double stamp_s, double true_roll_rad, double true_pitch_rad) {
  Odometry o;
  o.stamp_s = stamp_s;
  o.T_odom_base = pose_;
  o.velocity = velocity_;
  o.roll_rad = true_roll_rad + rng_.normal(0.0, params_.imu_tilt_noise_rad);
  o.pitch_rad = true_pitch_rad + rng_.normal(0.0, params_.imu_tilt_noise_rad);
  return o;
}

}  // namespace bipednav::sim
