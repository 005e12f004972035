#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "bipednav/planning/local/moving_obstacle_params.hpp"
#include "tracking/tracking_test_utils.hpp"

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

using tracking::test::digit_sensors;
using tracking::test::digit_visibility;

}  // namespace bipednav::planning::local
