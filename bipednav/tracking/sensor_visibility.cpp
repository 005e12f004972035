#include "bipednav/tracking/sensor_visibility.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "bipednav/common/error.hpp"

namespace bipednav::tracking {

namespace {

bool positive_angle(double v) { return std::isfinite(v) && v > 0.0; }

}  // namespace

void SensorVisibilityParams::validate() const {
  require(std::isfinite(lidar_min_elevation_rad) && std::isfinite(lidar_max_elevation_rad) &&
              lidar_min_elevation_rad < lidar_max_elevation_rad,
          "sensor_visibility.lidar_min_elevation_rad", "finite and < lidar_max_elevation_rad");
  require(std::isfinite(lidar_min_range_m) && lidar_min_range_m >= 0.0 && lidar_min_range_m < lidar_max_range_m,
          "sensor_visibility.lidar_min_range_m", "in [0, lidar_max_range_m)");
  require(positive_angle(depth_hfov_rad) && depth_hfov_rad < std::numbers::pi, "sensor_visibility.depth_hfov_rad",
          "in (0, pi)");
  require(positive_angle(depth_vfov_rad) && depth_vfov_rad < std::numbers::pi, "sensor_visibility.depth_vfov_rad",
          "in (0, pi)");
  require(std::isfinite(depth_min_range_m) && depth_min_range_m >= 0.0 && depth_min_range_m < depth_max_range_m,
          "sensor_visibility.depth_min_range_m", "in [0, depth_max_range_m)");
  require(std::isfinite(min_obstacle_height_m) && min_obstacle_height_m >= 0.0,
          "sensor_visibility.min_obstacle_height_m", ">= 0");
}

SensorVisibility::SensorVisibility(const RobotProfile& robot, SensorVisibilityParams params)
    : params_(std::move(params)) {
  params_.validate();
  for (const auto& m : robot.sensors) {
    if (m.type == "vlp16") lidars_.emplace_back(m.x_m, m.y_m, m.z_m);
    if (m.type == "d430") cameras_.push_back(m.T_base_sensor().inverse());
  }
}

bool SensorVisibility::sees_base_point(const Eigen::Vector3d& p) const {
  if (!p.allFinite()) return false;
  for (const auto& o : lidars_) {
    const Eigen::Vector3d v = p - o;
    const double r = v.norm();
    const double elevation = std::atan2(v.z(), std::hypot(v.x(), v.y()));
    if (r >= params_.lidar_min_range_m && r <= params_.lidar_max_range_m &&
        elevation >= params_.lidar_min_elevation_rad && elevation <= params_.lidar_max_elevation_rad)
      return true;
  }
  const double th = std::tan(0.5 * params_.depth_hfov_rad), tv = std::tan(0.5 * params_.depth_vfov_rad);
  for (const auto& T : cameras_) {
    const Eigen::Vector3d q = T * p;  // x along the optical axis, y left, z up
    if (q.x() < params_.depth_min_range_m || q.norm() > params_.depth_max_range_m) continue;
    if (std::abs(q.y()) <= q.x() * th && std::abs(q.z()) <= q.x() * tv) return true;
  }
  return false;
}

bool SensorVisibility::sees(const Pose2& robot, const Eigen::Vector2d& p, double top_m) const {
  const Eigen::Vector2d b = robot.inverse().transform(p);
  // Samples of the segment from the lowest obstacle height to the top (the top alone decides for a
  // LiDAR looking down at it; a pitched camera may see only its lower part).
  constexpr int kSamples = 5;
  const double lo = std::min(params_.min_obstacle_height_m, top_m);
  for (int k = 0; k < kSamples; ++k) {
    const double z = lo + (top_m - lo) * k / (kSamples - 1);
    if (sees_base_point({b.x(), b.y(), z})) return true;
  }
  return false;
}

}  // namespace bipednav::tracking
