#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "bipednav/common/point_cloud.hpp"
#include "bipednav/common/rng.hpp"
#include "bipednav/common/se3.hpp"

namespace bipednav::test {

// An oriented box; `inside` boxes are rooms (rays hit their walls from within).
struct SceneBox {
  SE3 T_world_box = SE3::Identity();
  Eigen::Vector3d half_size{1, 1, 1};
  bool inside = false;
};

// A scene of boxes with an analytic ray caster, for LiDAR tests that need no simulator.
struct SyntheticScene {
  std::vector<SceneBox> boxes;
  // Range along the unit ray, if anything is hit within max_range.
  std::optional<double> cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double max_range) const;
};

// A 12 x 8 x 3 m room with pillars and boxes (some rotated), floor at z = 0.
SyntheticScene room_scene();
// A straight corridor, 2 m wide and 3 m high, much longer than the LiDAR range (along x).
SyntheticScene corridor_scene();

struct SweepSpec {
  int rings = 16;
  int columns = 900;  // per revolution
  double period_s = 0.1;
  double noise_m = 0.0;  // Gaussian range noise
  double max_range_m = 100.0;
};

// A VLP-16-like sweep starting at t0: column c fires at t0 + c * period / columns from the pose
// T_world_lidar_at(t); points are in the LiDAR frame at their firing time, with time offsets and
// rings. `world_points`, when given, receives the noise-free world position of each point.
PointCloud synthetic_sweep(const SyntheticScene& scene, const std::function<SE3(double)>& T_world_lidar_at, double t0,
                           const SweepSpec& spec, Rng& rng, std::vector<Eigen::Vector3d>* world_points = nullptr);

}  // namespace bipednav::test
