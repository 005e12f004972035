#pragma once

#include <cmath>

namespace bipednav {

// A planar velocity command in the base frame: forward, lateral (m/s) and yaw rate (rad/s).
// Walking robots in this project take linear_x and angular_z only; linear_y stays 0.
struct Twist {
  double linear_x = 0.0;
  double linear_y = 0.0;
  double angular_z = 0.0;

  bool is_zero() const { return linear_x == 0.0 && linear_y == 0.0 && angular_z == 0.0; }
  bool is_finite() const { return std::isfinite(linear_x) && std::isfinite(linear_y) && std::isfinite(angular_z); }
};

}  // namespace bipednav
