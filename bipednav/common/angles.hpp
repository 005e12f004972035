#pragma once

#include <cmath>
#include <numbers>

namespace bipednav {

// Wraps an angle to (-pi, pi].
inline double normalize_angle(double a) {
  a = std::remainder(a, 2.0 * std::numbers::pi);
  return a <= -std::numbers::pi ? a + 2.0 * std::numbers::pi : a;
}

// Signed shortest difference a - b, in (-pi, pi].
inline double angle_diff(double a, double b) { return normalize_angle(a - b); }

inline constexpr double deg2rad(double d) { return d * std::numbers::pi / 180.0; }
inline constexpr double rad2deg(double r) { return r * 180.0 / std::numbers::pi; }

}  // namespace bipednav
