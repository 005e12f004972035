#pragma once

#include <cstdint>

#include "bipednav/common/rng.hpp"
#include "bipednav/common/sensor_frame.hpp"
#include "bipednav/common/twist.hpp"

namespace bipednav::sim {

// Wheel / leg odometry drift. Scale errors and the yaw bias are fixed (systematic); the random
// walks come from white velocity noise, so position/heading error grows with sqrt(time).
struct OdometryParams {
  double rate_hz = 50.0;
  double linear_scale_error = 0.02;  // measured = true * (1 + error)
  double angular_scale_error = 0.01;
  double yaw_bias_radps = 0.002;
  double linear_random_walk_m_per_sqrt_s = 0.005;
  double yaw_random_walk_rad_per_sqrt_s = 0.002;
  double imu_tilt_noise_rad = 0.002;  // roll / pitch noise

  void validate() const;
};

// Integrates the true body velocity into a drifting pose in the odom frame (which starts at the
// identity, i.e. at the robot's start pose).
class OdometryModel {
 public:
  OdometryModel(const OdometryParams& params, std::uint64_t seed);

  // Adds one interval of true body motion.
  void integrate(const Twist& true_body_velocity, double dt_s);
  // The current reading, with IMU roll/pitch (true values plus noise).
  Odometry measure(double stamp_s, double true_roll_rad, double true_pitch_rad);

  const Pose2& pose() const { return pose_; }
  const OdometryParams& params() const { return params_; }

 private:
  OdometryParams params_;
  Rng rng_;
  Pose2 pose_;
  Twist velocity_;
};

}  // namespace bipednav::sim
