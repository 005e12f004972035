#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "bipednav/common/robot_profile.hpp"
#include "bipednav/common/sensor_frame.hpp"

namespace bipednav::bench {

// A synthetic stand-in for the simulator, for tests and benchmarks of perception: a flat floor
// (z = 0 of the base frame) in a walled room with boxes, seen by analytic ray casting.
struct SyntheticBox {
  Eigen::Vector3d min_m, max_m;  // axis-aligned, base frame
};

struct SyntheticSceneParams {
  double room_x_m = 10.0, room_y_m = 8.0, wall_height_m = 2.5;  // the thesis' 10 x 8 m lab, centred on the robot
  std::vector<SyntheticBox> boxes = {
      {{1.0, -0.3, 0.0}, {1.4, 0.3, 0.8}}, {{-1.8, 0.5, 0.0}, {-1.3, 1.0, 1.2}}, {{3.0, -2.0, 0.0}, {3.5, -1.2, 0.5}}};
  int depth_width = 424, depth_height = 240;
  double depth_hfov_rad = 85.0 * M_PI / 180.0, depth_vfov_rad = 58.0 * M_PI / 180.0;
  double depth_min_m = 0.2, depth_max_m = 10.0;
  double depth_noise_per_m2 = 0.002;  // sigma = this * range^2
  int lidar_rings = 16;               // VLP-16: -15 .. +15 deg
  double lidar_azimuth_step_rad = 0.2 * M_PI / 180.0;
  double lidar_max_m = 100.0, lidar_noise_m = 0.01;
  std::uint64_t seed = 7;
};

// Digit's sensor suite as the issue describes it: a VLP-16 on top of the torso (1.47 m, so its
// lowest ring meets the floor ~5.5 m away) and two D430 at the pelvis pitched 45 deg down, one to
// the front and one to the back.
RobotProfile synthetic_digit_profile();

// One frame: both depth clouds (camera frames, NaN where nothing is hit) and one LiDAR sweep
// (lidar frame, with rings and time offsets over 0.1 s).
SensorFrame synthetic_digit_frame(const RobotProfile& robot, const SyntheticSceneParams& params = {});

}  // namespace bipednav::bench
