#pragma once

#include <Eigen/Core>
#include <vector>

#include "bipednav/common/pose2.hpp"
#include "bipednav/common/robot_profile.hpp"
#include "bipednav/common/se3.hpp"

namespace bipednav::tracking {

// Where the robot's range sensors can see an obstacle: a VLP-16 sees a point whose elevation from
// the sensor is within its rings' span (so a low object only beyond z_lidar / tan(15 deg) minus its
// height), a depth camera a point inside its pinhole frustum and range. Occlusion is not modelled:
// an occluded track counts as visible and is dropped as before. The robot's base is on the floor
// (z = 0); an obstacle is a vertical segment from min_obstacle_height_m to its top.
struct SensorVisibilityParams {
  double lidar_min_elevation_rad = -0.2617993877991494;  // VLP-16: -15 deg
  double lidar_max_elevation_rad = 0.2617993877991494;
  double lidar_min_range_m = 0.3;
  double lidar_max_range_m = 100.0;
  double depth_hfov_rad = 1.4835298641951802;  // D430: 85 x 58 deg
  double depth_vfov_rad = 1.0122909661567112;
  double depth_min_range_m = 0.2;       // along the optical axis
  double depth_max_range_m = 2.9;       // from the camera (the perception pipeline's range filter)
  double min_obstacle_height_m = 0.05;  // lower points are not obstacles (perception)

  void validate() const;
};

class SensorVisibility {
 public:
  SensorVisibility() = default;  // no sensors: nothing is visible
  // The profile's vlp16 and d430 mounts.
  SensorVisibility(const RobotProfile& robot, SensorVisibilityParams params);

  // Whether some sensor sees a part of the vertical segment at `p` (map frame) from its base to top_m,
  // with the robot at `robot` (map frame).
  bool sees(const Pose2& robot, const Eigen::Vector2d& p, double top_m) const;
  // Whether some sensor sees the point (x, y, z) given in the robot's base frame.
  bool sees_base_point(const Eigen::Vector3d& p_base) const;
  bool empty() const { return lidars_.empty() && cameras_.empty(); }

 private:
  SensorVisibilityParams params_;
  std::vector<Eigen::Vector3d> lidars_;  // origins in the base frame
  std::vector<SE3> cameras_;             // T_sensor_base
};

}  // namespace bipednav::tracking
