#pragma once

#include <Eigen/Core>
#include <cmath>

namespace bipednav::tracking {

// One object seen in one sensor cycle (map frame): the measurement a track is updated with.
struct Detection {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();               // estimated centre
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity() * 0.01;  // of position (m^2)
  double radius_m = 0.0;                                            // the points' largest distance from the centre
  // The near surface on the line of sight through the middle of the points (where the object was
  // seen, as opposed to its estimated centre).
  Eigen::Vector2d surface = Eigen::Vector2d::Zero();
  double top_m = 0.0;  // highest point above the floor (0: heights unknown)
  // Highest minus lowest point: a vertical surface spans heights, the top of a box lower than a
  // LiDAR does not (-1: heights unknown).
  double height_span_m = -1.0;
  int points = 0;

  bool finite() const { return position.allFinite() && covariance.allFinite() && std::isfinite(radius_m); }
};

}  // namespace bipednav::tracking
