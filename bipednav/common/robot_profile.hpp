#pragma once

#include <string>
#include <vector>

#include "bipednav/common/error.hpp"
#include "bipednav/common/se3.hpp"
#include "bipednav/common/velocity_limits.hpp"

namespace bipednav {

// A sensor mount: the transform from the base frame to the sensor frame (T_base_sensor).
// Sensor frames follow REP-103: x forward, y left, z up (also for depth cameras).
struct SensorMount {
  std::string name;  // "lidar", "depth_front", "depth_back", "depth_head"
  std::string type;  // "vlp16" or "d430"
  double x_m = 0.0, y_m = 0.0, z_m = 0.0;
  double roll_rad = 0.0, pitch_rad = 0.0, yaw_rad = 0.0;

  SE3 T_base_sensor() const { return make_se3(x_m, y_m, z_m, roll_rad, pitch_rad, yaw_rad); }
};

// Kinematic and geometric description of a robot, shared by the simulator and the planners.
struct RobotProfile {
  std::string name = "turtlebot3";
  std::string kind = "diff_drive";  // "diff_drive", "walker" (velocity-commanded biped), "humanoid" (footsteps)
  double footprint_radius_m = 0.2;  // circumscribed radius of the footprint (a circle)
  double height_m = 0.5;
  VelocityLimits limits;                   // forward/yaw only (max_vel_y_mps = 0)
  double tracking_time_constant_s = 0.05;  // first-order lag of the velocity controller
  double sway_amplitude_m = 0.0;           // lateral sway of a walker's base
  double step_frequency_hz = 0.0;          // steps per second of a walker
  bool can_rotate_in_place = true;
  std::vector<SensorMount> sensors;

  void validate() const {
    require(!name.empty(), "name", "a non-empty robot name");
    require(kind == "diff_drive" || kind == "walker" || kind == "humanoid", "kind",
            "one of diff_drive, walker, humanoid");
    require(footprint_radius_m > 0.0 && footprint_radius_m < 5.0, "footprint_radius_m", "in (0, 5) m");
    require(height_m > 0.0, "height_m", "> 0");
    limits.validate();
    require(tracking_time_constant_s >= 0.0, "tracking_time_constant_s", ">= 0");
    require(sway_amplitude_m >= 0.0, "sway_amplitude_m", ">= 0");
    require(step_frequency_hz >= 0.0, "step_frequency_hz", ">= 0");
    for (const auto& s : sensors) {
      require(!s.name.empty(), "sensors[].name", "a non-empty sensor name");
      require(s.type == "vlp16" || s.type == "d430", "sensors[" + s.name + "].type", "vlp16 or d430");
    }
  }
  // The LiDAR the stack uses (LOAM, the obstacle layers, the sensor gate): the first vlp16 mount.
  const SensorMount* lidar() const {
    for (const auto& s : sensors)
      if (s.type == "vlp16") return &s;
    return nullptr;
  }
  const SensorMount* sensor(const std::string& sensor_name) const {
    for (const auto& s : sensors)
      if (s.name == sensor_name) return &s;
    return nullptr;
  }
};

}  // namespace bipednav
