#pragma once

#include <Eigen/Core>
#include <cmath>

#include "bipednav/common/angles.hpp"

namespace bipednav {

// A planar pose (x, y, theta) in SI units; composition follows SE(2).
struct Pose2 {
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;

  Eigen::Vector2d position() const { return {x, y}; }
  bool operator==(const Pose2&) const = default;

  // this * other: other expressed in this frame, returned in the parent frame.
  Pose2 operator*(const Pose2& o) const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {x + c * o.x - s * o.y, y + s * o.x + c * o.y, normalize_angle(theta + o.theta)};
  }
  Pose2 inverse() const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {-c * x - s * y, s * x - c * y, normalize_angle(-theta)};
  }
  Eigen::Vector2d transform(const Eigen::Vector2d& p) const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {x + c * p.x() - s * p.y(), y + s * p.x() + c * p.y()};
  }
  bool is_finite() const { return std::isfinite(x) && std::isfinite(y) && std::isfinite(theta); }
};

inline double distance(const Pose2& a, const Pose2& b) { return std::hypot(a.x - b.x, a.y - b.y); }

}  // namespace bipednav
