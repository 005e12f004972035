#include "bipednav/perception/voxel_grid.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "bipednav/common/error.hpp"

namespace bipednav::perception {

void VoxelGridParams::validate() const {
  for (int a = 0; a < 3; ++a)
    require(std::isfinite(leaf_size_m[a]) && leaf_size_m[a] > 0.0, "leaf_size_m", "three finite sizes > 0 m");
}

namespace {

constexpr std::int64_t kAxisBits = 21;
constexpr std::int64_t kAxisHalf = std::int64_t{1} << (kAxisBits - 1);

// Open addressing with linear probing; a slot holds key + 1 (0 = empty) and the voxel's index.
class VoxelTable {
 public:
  explicit VoxelTable(std::size_t n) {
    const std::size_t cap = std::bit_ceil(std::max<std::size_t>(16, 2 * n));
    keys_.assign(cap, 0);
    index_.resize(cap);
    mask_ = cap - 1;
    shift_ = 64 - std::countr_zero(cap);
  }
  // Index of the voxel with `key`; a new voxel gets `next` and `inserted` is set.
  std::uint32_t find_or_insert(std::uint64_t key, std::uint32_t next, bool& inserted) {
    const std::uint64_t stored = key + 1;
    std::size_t s = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_);
    while (true) {
      if (keys_[s] == stored) {
        inserted = false;
        return index_[s];
      }
      if (keys_[s] == 0) {
        keys_[s] = stored;
        index_[s] = next;
        inserted = true;
        return next;
      }
      s = (s + 1) & mask_;
    }
  }

 private:
  std::vector<std::uint64_t> keys_;
  std::vector<std::uint32_t> index_;
  std::size_t mask_ = 0;
  int shift_ = 0;
};

struct Accumulator {
  double x = 0.0, y = 0.0, z = 0.0, intensity = 0.0, time = 0.0;
  std::uint32_t count = 0;
  std::uint32_t first = 0;  // index of the first input point (ring source)
};

std::uint64_t voxel_key(const Eigen::Vector3f& p, const Eigen::Vector3d& inv_leaf) {
  std::uint64_t key = 0;
  for (int a = 0; a < 3; ++a) {
    const double c = std::floor(static_cast<double>(p[a]) * inv_leaf[a]);
    if (!(c >= -static_cast<double>(kAxisHalf) && c < static_cast<double>(kAxisHalf)))
      throw Error("voxel_downsample: point coordinate " + std::to_string(p[a]) +
                  " is too far from the origin for the leaf size (key overflow); increase leaf_size_m");
    key = (key << kAxisBits) | static_cast<std::uint64_t>(static_cast<std::int64_t>(c) + kAxisHalf);
  }
  return key;
}

PointCloud centroids(const PointCloud& in, const std::vector<Accumulator>& acc) {
  PointCloud out = in.empty_copy();
  const std::size_t m = acc.size();
  out.points.resize(m);
  if (in.has_intensity()) out.intensities.resize(m);
  if (in.has_time()) out.time_offsets_s.resize(m);
  if (in.has_ring()) out.rings.resize(m);
  for (std::size_t v = 0; v < m; ++v) {
    const Accumulator& a = acc[v];
    const double inv = 1.0 / a.count;
    out.points[v] =
        Eigen::Vector3f(static_cast<float>(a.x * inv), static_cast<float>(a.y * inv), static_cast<float>(a.z * inv));
    if (in.has_intensity()) out.intensities[v] = static_cast<float>(a.intensity * inv);
    if (in.has_time()) out.time_offsets_s[v] = static_cast<float>(a.time * inv);
    if (in.has_ring()) out.rings[v] = in.rings[a.first];
  }
  return out;
}

}  // namespace

PointCloud voxel_downsample(const PointCloud& in, const VoxelGridParams& params) {
  params.validate();
  if (!in.is_consistent()) throw Error("voxel_downsample: the cloud's optional fields do not match its point count");
  const Eigen::Vector3d inv_leaf = params.leaf_size_m.cwiseInverse();
  const std::size_t n = in.size();
  VoxelTable table(n);
  std::vector<Accumulator> acc;
  acc.reserve(n / 4 + 16);
  const bool with_i = in.has_intensity(), with_t = in.has_time();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3f& p = in.points[i];
    if (!p.allFinite()) continue;
    bool inserted = false;
    const std::uint32_t v =
        table.find_or_insert(voxel_key(p, inv_leaf), static_cast<std::uint32_t>(acc.size()), inserted);
    if (inserted) acc.push_back({0.0, 0.0, 0.0, 0.0, 0.0, 0, static_cast<std::uint32_t>(i)});
    Accumulator& a = acc[v];
    a.x += p.x();
    a.y += p.y();
    a.z += p.z();
    if (with_i) a.intensity += in.intensities[i];
    if (with_t) a.time += in.time_offsets_s[i];
    ++a.count;
  }
  return centroids(in, acc);
}

}  // namespace bipednav::perception
