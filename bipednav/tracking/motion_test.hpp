#pragma once

#include <Eigen/Core>
#include <span>

namespace bipednav::tracking {

struct TimedPosition {
  double t_s = 0.0;
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  Eigen::Vector2d surface = Eigen::Vector2d::Zero();  // a point of the surface seen (not used here)
};

// The least-squares line through positions over time, per axis: its slope (the velocity over the
// window) and the slope's standard error from the residuals (pooled over both axes, 2n - 4
// degrees of freedom). A static object's measured centre jitters as the sensors see more or less
// of it, which the residuals show; a mover's centre runs along the line.
struct WindowVelocity {
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();
  double standard_error_mps = 0.0;  // of each velocity component
  int samples = 0;
  double span_s = 0.0;  // from the first sample to the last
  // Whether the speed is at least min_speed_mps and min_significance standard errors.
  bool moving(double min_speed_mps, double min_significance) const {
    const double v = velocity.norm();
    return samples >= 3 && v >= min_speed_mps && v >= min_significance * standard_error_mps;
  }
};

// Needs three samples at distinct times at least; fewer give samples < 3 and no velocity.
WindowVelocity regression_velocity(std::span<const TimedPosition> samples);

}  // namespace bipednav::tracking
