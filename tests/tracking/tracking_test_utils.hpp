#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "bipednav/common/pose2.hpp"
#include "bipednav/common/rng.hpp"
#include "bipednav/common/robot_profile.hpp"
#include "bipednav/mapping/costmap2d.hpp"
#include "bipednav/tracking/sensor_visibility.hpp"

// Helpers shared by the tracking tests (and the moving-obstacle tests of planning/local).
namespace bipednav::tracking::test {

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

// A free square grid of side size_m centred at (cx, cy).
inline mapping::Costmap2D free_grid(double cx, double cy, double size_m, double resolution_m) {
  const int cells = static_cast<int>(std::lround(size_m / resolution_m));
  return mapping::Costmap2D({cells, cells, resolution_m, cx - 0.5 * size_m, cy - 0.5 * size_m}, mapping::kFree);
}

// One scan of a planar range sensor at `viewpoint`: a ray every 0.25 deg towards a vertical
// cylinder at `center` of `radius_m` and `top_m` tall returns the cylinder's near surface, with
// Gaussian range noise of noise_m, at heights 0.2 m apart from 0.1 m up to the top (the rings of a
// LiDAR on a vertical surface). Rays longer than 8 m return nothing.
struct Scan {
  std::vector<Eigen::Vector2d> points;
  std::vector<double> heights;
};

inline void scan_cylinder(Scan& scan, const Eigen::Vector2d& viewpoint, const Eigen::Vector2d& center, double radius_m,
                          double top_m, double noise_m, Rng& rng) {
  const Eigen::Vector2d c = center - viewpoint;
  const double bearing = std::atan2(c.y(), c.x()), dist = c.norm();
  if (!(dist > radius_m)) return;
  const double half = std::asin(radius_m / dist), step = 0.25 * M_PI / 180.0;
  for (double a = std::ceil((bearing - half) / step) * step; a <= bearing + half; a += step) {
    const Eigen::Vector2d u(std::cos(a), std::sin(a));
    const double b = u.dot(c), disc = b * b - (c.squaredNorm() - radius_m * radius_m);
    if (disc < 0.0) continue;
    const double range = b - std::sqrt(disc);
    if (range > 8.0) continue;
    for (double z = 0.1; z <= top_m; z += 0.2) {
      scan.points.push_back(viewpoint + u * (range + rng.normal(0.0, noise_m)));
      scan.heights.push_back(z);
    }
  }
}

}  // namespace bipednav::tracking::test
