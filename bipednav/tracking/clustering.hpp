#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <span>
#include <vector>

namespace bipednav::tracking {

// Euclidean clustering on a grid: the points (x, y used; z ignored) are binned into square cells
// of cell_m; the points of 8-connected occupied cells form one cluster (points closer than cell_m
// always share one). Clusters of fewer than min_points points are dropped. Each cluster lists its
// point indices ascending; clusters are ordered by their first point. Non-finite points are
// skipped, as are points so far out (beyond 1e9 cells) that no cell index holds them.
std::vector<std::vector<std::size_t>> euclidean_clusters(std::span<const Eigen::Vector3d> points, double cell_m,
                                                         int min_points);

}  // namespace bipednav::tracking
