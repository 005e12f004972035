#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "bipednav/common/point_cloud.hpp"
#include "bipednav/perception/pass_through.hpp"

namespace bipednav::perception {

struct VoxelGridParams {
  Eigen::Vector3d leaf_size_m{0.02, 0.02, 0.02};  // voxel edge per axis (the thesis: 0.02 m)

  void validate() const;
};

namespace detail {
struct VoxelAccumulator {
  std::uint64_t key = 0;
  double x = 0.0, y = 0.0, z = 0.0, intensity = 0.0, time = 0.0;
  std::uint32_t count = 0;
  std::uint32_t first = 0;  // index of the first input point (ring source)
};
}  // namespace detail

// Voxel-grid downsampling (section 4.2.1): every occupied voxel is replaced by the centroid of its
// points. Voxels are found through a hash table keyed by the integer voxel coordinates (no sort),
// and the output lists voxels in the order of their first point in the input, so the result is
// deterministic. Non-finite points are dropped. Optional fields: intensity and time offset are
// averaged over the voxel (the mean firing time matches the centroid), the ring is the first
// point's. Frame and stamp are copied. Throws Error when the cloud spans more than 2^21 voxels on
// an axis (the key would overflow: increase the leaf size).
//
// The object keeps its hash table and accumulators between calls, so a pipeline that filters a
// cloud every frame does not allocate (and page-fault) them again.
class VoxelGrid {
 public:
  explicit VoxelGrid(const VoxelGridParams& params = {});

  // Downsamples the points of `in` that pass `crop` (every finite point when null) into `out`,
  // whose contents are replaced (`out` must not be `in`).
  void filter(const PointCloud& in, PointCloud& out, const PassThroughTest* crop = nullptr);
  PointCloud filter(const PointCloud& in) {
    PointCloud out;
    filter(in, out);
    return out;
  }
  const VoxelGridParams& params() const { return params_; }

 private:
  std::uint32_t find_or_insert(std::uint64_t key, std::uint32_t point);
  void rebuild(std::size_t capacity);
  void write_centroids(const PointCloud& in, PointCloud& out) const;

  VoxelGridParams params_;
  Eigen::Vector3d inv_leaf_;
  std::vector<detail::VoxelAccumulator> acc_;
  std::vector<std::uint32_t> slots_;  // open addressing, linear probing: index into acc_
  std::vector<std::uint64_t> keys_;   // voxel key per input point
  std::size_t mask_ = 0;
  int shift_ = 0;
};

// One-shot form of VoxelGrid::filter.
PointCloud voxel_downsample(const PointCloud& in, const VoxelGridParams& params);

}  // namespace bipednav::perception
