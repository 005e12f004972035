#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "bipednav/common/robot_profile.hpp"
#include "bipednav/planning/local/moving_obstacle_params.hpp"
#include "bipednav/planning/local/sensor_visibility.hpp"

// Helpers shared by the moving-obstacle tests.
namespace bipednav::planning::local {

// The outline of an axis-aligned square of side `side` centred at c, a point every 2 cm, with a
// deterministic jitter of up to 1 cm.
inline void add_square(std::vector<Eigen::Vector2d>& pts, const Eigen::Vector2d& c, double side, int salt) {
  const int n = static_cast<int>(side / 0.02);
  for (int i = 0; i <= n; ++i) {
    const double s = -0.5 * side + i * 0.02;
    const double j = 0.01 * std::sin(1.7 * i + 0.9 * salt);
    pts.emplace_back(c.x() + s, c.y() - 0.5 * side + j);
    pts.emplace_back(c.x() + s, c.y() + 0.5 * side - j);
    pts.emplace_back(c.x() - 0.5 * side + j, c.y() + s);
    pts.emplace_back(c.x() + 0.5 * side - j, c.y() + s);
  }
}

inline void add_wall(std::vector<Eigen::Vector2d>& pts, double x0, double x1, double y) {
  for (double x = x0; x <= x1; x += 0.03) pts.emplace_back(x, y);
}

inline MovingObstacleParams enabled_tracking() {
  MovingObstacleParams p;
  p.enabled = true;
  return p;
}

// Digit's range sensors (config/digit.yaml): a VLP-16 at 1.474 m and two D430s at the pelvis
// (0.95 m), pitched 45 deg down, facing forward and back.
inline RobotProfile digit_sensors() {
  RobotProfile r;
  const double pitch = 0.25 * M_PI;
  r.sensors = {{"lidar", "vlp16", 0.0, 0.0, 1.474},
               {"depth_front", "d430", 0.1, 0.0, 0.95, 0.0, pitch, 0.0},
               {"depth_back", "d430", -0.1, 0.0, 0.95, 0.0, pitch, M_PI}};
  return r;
}

inline SensorVisibility digit_visibility() { return SensorVisibility(digit_sensors(), SensorVisibilityParams{}); }

}  // namespace bipednav::planning::local
