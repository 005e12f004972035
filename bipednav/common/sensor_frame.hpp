#pragma once

#include <optional>
#include <vector>

#include "bipednav/common/point_cloud.hpp"
#include "bipednav/common/pose2.hpp"
#include "bipednav/common/se3.hpp"
#include "bipednav/common/twist.hpp"

namespace bipednav {

// Odometry as the robot's walking controller (or wheel encoders) reports it, in the odom frame.
struct Odometry {
  double stamp_s = 0.0;
  Pose2 T_odom_base;
  Twist velocity;          // in the base frame
  double roll_rad = 0.0;   // from the IMU
  double pitch_rad = 0.0;  // from the IMU
};

// A depth cloud with the camera it came from (mount name as in the robot profile).
struct DepthCloud {
  std::string camera;  // e.g. "depth_front", "depth_back"
  PointCloud cloud;    // in the camera's optical frame convention of the profile (x fwd, z up)
};

// Everything the sensors produced during one simulation (or driver) step. A sensor that
// produced nothing this step leaves its member empty; consumers must not assume a rate.
struct SensorFrame {
  double stamp_s = 0.0;
  std::optional<PointCloud> lidar;  // a full sweep, in the lidar frame, with time offsets and rings
  std::vector<DepthCloud> depth;    // depth clouds completed this step
  std::optional<Odometry> odometry;
};

}  // namespace bipednav
