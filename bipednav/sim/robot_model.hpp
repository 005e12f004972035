#pragma once

#include "bipednav/common/body_response.hpp"
#include "bipednav/common/pose2.hpp"
#include "bipednav/common/robot_profile.hpp"
#include "bipednav/common/twist.hpp"

namespace bipednav::sim {

// True kinematic state of the simulated robot (base frame at ground level under its centre).
struct RobotState {
  Pose2 pose;      // in the world frame
  Twist velocity;  // true body velocity in the base frame
  double roll_rad = 0.0;
  double pitch_rad = 0.0;
};

// Velocity-commanded robot from a RobotProfile.
// - diff_drive: forward speed and yaw rate (lateral ignored), first-order tracking with time
//   constant tracking_time_constant_s, acceleration limits, speeds clamped to the profile.
// - walker / humanoid: the same tracking of forward speed and yaw rate (the walking
//   controller's velocity interface), plus a lateral sway of the base,
//   sway_amplitude_m * sin(pi * step_frequency_hz * t): one left-right cycle per stride (two
//   steps). The gait never stops (Digit steps in place), so the base sways at rest too.
// Velocities are constant within a step; poses follow exact arcs, so pose_in_last_step() gives
// the exact pose at any instant of the last step (used for per-point sensor timing).
class RobotModel {
 public:
  explicit RobotModel(const RobotProfile& profile, const Pose2& start = {});

  // Advances by dt_s under cmd (a non-finite command or dt raises Error).
  const RobotState& step(const Twist& cmd, double dt_s);
  // True pose at tau_s in [0, dt] after the start of the last step.
  Pose2 pose_in_last_step(double tau_s) const;

  const RobotState& state() const { return state_; }
  const RobotProfile& profile() const { return profile_; }
  double time_s() const { return time_s_; }

 private:
  Pose2 sway_offset(double t_s) const;
  double sway_rate_mps(double t_s) const;

  RobotProfile profile_;
  bool walker_;
  double time_s_ = 0.0;
  double step_start_s_ = 0.0;
  Pose2 nominal_;  // pose without sway
  Pose2 step_start_nominal_;
  double v_ = 0.0, w_ = 0.0;  // tracked forward speed and yaw rate
  RobotState state_;
};

}  // namespace bipednav::sim
