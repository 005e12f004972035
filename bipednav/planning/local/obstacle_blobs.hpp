#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "bipednav/planning/local/moving_obstacle_params.hpp"

namespace bipednav::planning::local {

// A blob of one cycle: centroid and bounding radius of its points.
struct Blob {
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  double radius_m = 0.0;
  double top_m = 0.0;  // highest point (0: heights unknown)
  int points = 0;
};

// cluster_blobs' buffers, kept between calls by their owner (it runs at the local map's rate on
// tens of thousands of points). What they held does not change the blobs.
struct BlobScratch {
  std::vector<long> bx, by;
  std::vector<std::size_t> in_range, order, stack, members;
  std::vector<std::uint32_t> start;
  std::vector<std::int32_t> grid;  // dense: cell index per bin, -1 when empty
  std::vector<std::pair<std::size_t, std::size_t>> cells;
  std::vector<std::pair<long, long>> cell_xy;
  std::vector<char> seen;
};

// Clusters 2D points (map frame) within max_range_m of `center` into blobs; blobs larger than
// max_blob_radius_m or with fewer than min_points points are left out. Deterministic order.
// `heights` (empty, or one per point: height above the floor) gives the blobs' tops. Without
// `scratch` the call allocates its own buffers.
std::vector<Blob> cluster_blobs(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& center,
                                const MovingObstacleParams& params, const std::vector<double>& heights = {},
                                BlobScratch* scratch = nullptr);

}  // namespace bipednav::planning::local
