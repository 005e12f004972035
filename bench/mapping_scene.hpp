#pragma once

#include <Eigen/Core>
#include <vector>

#include "bipednav/common/pose2.hpp"
#include "bipednav/common/rng.hpp"
#include "bipednav/mapping/obstacle_layer.hpp"

namespace bipednav::bench {

// A synthetic Digit sensor frame for benchmarks (no simulator needed): a 10 x 8 m room centred on
// the origin with nine 0.25 m cylinders on a hexagon-like ring, seen by a VLP-16 (16 rings x 1800
// azimuths, 1.2 m high) and two depth cameras (front and back, 87 x 58 deg, 212 x 120 rays, 4 m,
// 1.0 m high), obstacle-height returns only (0.05..2.0 m), all in the map frame.
struct SyntheticObservations {
  std::vector<mapping::Observation> observations;  // lidar, depth_front, depth_back
  std::size_t lidar_points = 0;
  std::size_t depth_points = 0;
};
SyntheticObservations synthetic_digit_observations(const Pose2& T_map_base);

// `n` points of a bumpy terrain (steps and boxes up to 0.4 m, 1 cm noise) on a size_m square at
// the origin, in raster order (like an organised depth cloud), for heightmap benchmarks.
std::vector<Eigen::Vector3f> synthetic_terrain_cloud(std::size_t n, double size_m, Rng& rng);

}  // namespace bipednav::bench
