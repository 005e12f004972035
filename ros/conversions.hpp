#pragma once

// All conversions between bipednav's core types and ROS 1 messages live here (and only here);
// the nodes and the bag recorder are thin adapters on top of these functions.

#include <geometry_msgs/Pose.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <geometry_msgs/Twist.h>
#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/Odometry.h>
#include <nav_msgs/Path.h>
#include <ros/time.h>
#include <sensor_msgs/PointCloud2.h>
#include <visualization_msgs/MarkerArray.h>

#include <cstdint>
#include <optional>
#include <string>

#include "bipednav/common/path.hpp"
#include "bipednav/common/point_cloud.hpp"
#include "bipednav/common/pose2.hpp"
#include "bipednav/common/se3.hpp"
#include "bipednav/common/sensor_frame.hpp"
#include "bipednav/common/twist.hpp"
#include "bipednav/mapping/costmap2d.hpp"

namespace bipednav::ros1 {

ros::Time to_time(double stamp_s);

// PointCloud <-> PointCloud2 with float32 x, y, z, intensity, time (s since the header stamp)
// and uint16 ring fields, written by hand (no PCL). Missing optional fields are not written.
sensor_msgs::PointCloud2 to_msg(const PointCloud& cloud);
// Reads x, y, z (float32) and, when present, intensity (float32), time (float32 s, or float64)
// and ring (uint16). Non-finite points are dropped. Throws Error on a malformed message.
PointCloud from_msg(const sensor_msgs::PointCloud2& msg);

// Costmap (0 free .. 253 inscribed, 254 lethal, 255 unknown) -> occupancy 0..100, -1 unknown
// (the costmap_2d translation: 0 -> 0, 253 -> 99, 254 -> 100, 255 -> -1, linear in between).
std::int8_t occupancy_of(std::uint8_t cost);
nav_msgs::OccupancyGrid to_msg(const mapping::Costmap2D& map, const std::string& frame_id, double stamp_s);
// Back to the geometry and an approximate cost (exact for 0, 254, 255).
mapping::Costmap2D from_msg(const nav_msgs::OccupancyGrid& msg);

// Planar path <-> nav_msgs/Path (times_s go to each pose's header stamp, relative to the path's).
nav_msgs::Path to_msg(const Path& path, double stamp_s);
Path from_msg(const nav_msgs::Path& msg);

geometry_msgs::Twist to_msg(const Twist& t);
Twist from_msg(const geometry_msgs::Twist& msg);

geometry_msgs::Pose to_pose_msg(const Pose2& p);
// Yaw of the quaternion (roll and pitch ignored). Throws Error on non-finite values.
Pose2 from_msg(const geometry_msgs::Pose& msg);
geometry_msgs::PoseStamped to_pose_stamped(const Pose2& p, const std::string& frame_id, double stamp_s);

geometry_msgs::TransformStamped to_transform(const SE3& T_parent_child, const std::string& parent,
                                             const std::string& child, double stamp_s);
geometry_msgs::TransformStamped to_transform(const Pose2& T_parent_child, const std::string& parent,
                                             const std::string& child, double stamp_s);

nav_msgs::Odometry to_msg(const Odometry& odom, const std::string& odom_frame, const std::string& base_frame);
Odometry from_msg(const nav_msgs::Odometry& msg);

// What the markers show: the goal, the robot footprint, lethal cells of the local costmap
// (obstacles) and, for walking robots, alternating footsteps along the local trajectory.
struct MarkerInput {
  std::string frame_id = "map";
  double stamp_s = 0.0;
  Pose2 robot;
  double footprint_radius_m = 0.2;
  std::optional<Pose2> goal;
  const mapping::Costmap2D* local_costmap = nullptr;
  const Path* local_trajectory = nullptr;
  double step_length_m = 0.0;  // > 0: draw footsteps this far apart
  double step_width_m = 0.2;   // lateral distance between the feet
};
visualization_msgs::MarkerArray to_markers(const MarkerInput& in);

}  // namespace bipednav::ros1
