#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "bipednav/common/point_cloud.hpp"
#include "bipednav/perception/pass_through.hpp"

namespace bipednav::perception {

struct VoxelGridParams {
  Eigen::Vector3d leaf_size_m{0.02, 0.02, 0.02};  // voxel edge per axis (the thesis: 0.02 m)

  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v("leaf_size_m", leaf_size_m);
  }
};

namespace detail {
struct VoxelSum {
  double x = 0.0, y = 0.0, z = 0.0;
  std::uint32_t count = 0;
  std::uint32_t first = 0;  // index of the first input point (ring source)
};

// Packed integer voxel keys (21 bits per axis, x in the high bits) of points [0, n) of `xyz`
// (interleaved floats); kSkipKey for non-finite points. Returns false when a finite point is too
// far from the origin for the key (its key is kSkipKey too). The voxel of a point is
// floor(coordinate * inv_leaf) with the product in double, on every platform.
inline constexpr std::uint64_t kSkipKey = ~std::uint64_t{0};
bool voxel_keys(const float* xyz, std::size_t n, const Eigen::Vector3d& inv_leaf, std::uint64_t* keys);
}  // namespace detail

// Voxel-grid downsampling (section 4.2.1): every occupied voxel is replaced by the centroid of its
// points. Voxels are found through a hash table keyed by the integer voxel coordinates (no sort),
// and the output lists voxels in the order of their first point in the input, so the result is
// deterministic. Non-finite points are dropped. Optional fields: intensity and time offset are
// averaged over the voxel (the mean firing time matches the centroid), the ring is the first
// point's. Frame and stamp are copied. Throws Error when the cloud spans more than 2^21 voxels on
// an axis (the key would overflow: increase the leaf size).
//
// The object keeps its hash table and sums between calls, so a pipeline that filters a cloud every
// frame does not allocate (and page-fault) them again.
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
  template <bool kExtra>
  void accumulate(const PointCloud& in, std::size_t begin, std::size_t end);
  std::uint32_t find_or_insert(std::uint64_t key, std::uint32_t point);
  void rebuild(std::size_t capacity);
  void check_range(const PointCloud& in, std::size_t begin, std::size_t end, const PassThroughTest* crop) const;
  void write_centroids(const PointCloud& in, PointCloud& out) const;

  VoxelGridParams params_;
  Eigen::Vector3d inv_leaf_;
  std::vector<std::uint64_t> voxel_keys_;          // per voxel, in order of first appearance
  std::vector<detail::VoxelSum> sums_;             // per voxel
  std::vector<std::array<double, 2>> extra_sums_;  // intensity and time per voxel, when present
  std::vector<std::uint32_t> slots_;               // open addressing, linear probing: voxel index
  std::array<std::uint64_t, 256> block_keys_{};    // keys of the block of points being grouped
  bool with_extra_ = false;
  std::size_t mask_ = 0;
  int shift_ = 0;
};

// One-shot form of VoxelGrid::filter.
PointCloud voxel_downsample(const PointCloud& in, const VoxelGridParams& params);

}  // namespace bipednav::perception
