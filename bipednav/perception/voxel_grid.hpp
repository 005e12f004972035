#pragma once

#include <Eigen/Core>

#include "bipednav/common/point_cloud.hpp"

namespace bipednav::perception {

struct VoxelGridParams {
  Eigen::Vector3d leaf_size_m{0.02, 0.02, 0.02};  // voxel edge per axis (the thesis: 0.02 m)

  void validate() const;
};

// Voxel-grid downsampling (section 4.2.1): every occupied voxel is replaced by the centroid of its
// points. Voxels are found through a hash table keyed by the integer voxel coordinates (no sort),
// and the output lists voxels in the order of their first point in the input, so the result is
// deterministic. Non-finite points are dropped. Optional fields: intensity and time offset are
// averaged over the voxel (the mean firing time matches the centroid), the ring is the first
// point's. Frame and stamp are copied. Throws Error when the cloud spans more than 2^21 voxels on
// an axis (the key would overflow: increase the leaf size).
PointCloud voxel_downsample(const PointCloud& in, const VoxelGridParams& params);

}  // namespace bipednav::perception
