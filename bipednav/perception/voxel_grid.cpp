#include "bipednav/perception/voxel_grid.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "bipednav/common/error.hpp"

namespace bipednav::perception {

void VoxelGridParams::validate() const {
  for (int a = 0; a < 3; ++a)
    require(std::isfinite(leaf_size_m[a]) && leaf_size_m[a] > 0.0, "leaf_size_m", "three finite sizes > 0 m");
}

namespace {

constexpr std::int64_t kAxisBits = 21;
constexpr std::int64_t kAxisHalf = std::int64_t{1} << (kAxisBits - 1);
constexpr std::uint32_t kEmpty = 0xffffffffu;
constexpr std::size_t kMinSlots = 4096;

// floor() without a libm call (baseline x86-64 has no SSE4.1 round instruction).
inline std::int64_t floor_to_int(double v) {
  const auto i = static_cast<std::int64_t>(v);
  return i - (v < static_cast<double>(i) ? 1 : 0);
}

inline std::uint64_t voxel_key(const Eigen::Vector3f& p, const Eigen::Vector3d& inv_leaf) {
  std::uint64_t key = 0;
  for (int a = 0; a < 3; ++a) {
    const double scaled = static_cast<double>(p[a]) * inv_leaf[a];
    if (!(scaled >= -static_cast<double>(kAxisHalf) && scaled < static_cast<double>(kAxisHalf)))
      throw Error("voxel_downsample: point coordinate " + std::to_string(p[a]) +
                  " is too far from the origin for the leaf size (key overflow); increase leaf_size_m");
    key = (key << kAxisBits) | static_cast<std::uint64_t>(floor_to_int(scaled) + kAxisHalf);
  }
  return key;
}

}  // namespace

VoxelGrid::VoxelGrid(const VoxelGridParams& params) : params_(params) {
  params_.validate();
  inv_leaf_ = params_.leaf_size_m.cwiseInverse();
}

// A slot holds only the voxel's index (4 bytes, so the table stays in cache); the key is compared
// in the accumulator, which for spatially ordered input was touched recently. The table doubles
// at a quarter load (short probe sequences).
std::uint32_t VoxelGrid::find_or_insert(std::uint64_t key, std::uint32_t point) {
  std::size_t s = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_);
  while (true) {
    const std::uint32_t v = slots_[s];
    if (v == kEmpty) break;
    if (acc_[v].key == key) return v;
    s = (s + 1) & mask_;
  }
  const auto v = static_cast<std::uint32_t>(acc_.size());
  acc_.push_back({key, 0.0, 0.0, 0.0, 0.0, 0.0, 0, point});
  slots_[s] = v;
  if (4 * acc_.size() > slots_.size()) rebuild(2 * slots_.size());
  return v;
}

void VoxelGrid::rebuild(std::size_t capacity) {
  slots_.assign(capacity, kEmpty);
  mask_ = capacity - 1;
  shift_ = 64 - std::countr_zero(capacity);
  for (std::size_t v = 0; v < acc_.size(); ++v) {
    std::size_t s = static_cast<std::size_t>((acc_[v].key * 0x9E3779B97F4A7C15ull) >> shift_);
    while (slots_[s] != kEmpty) s = (s + 1) & mask_;
    slots_[s] = static_cast<std::uint32_t>(v);
  }
}

void VoxelGrid::write_centroids(const PointCloud& in, PointCloud& out) const {
  const std::size_t m = acc_.size();
  out.clear();
  out.frame_id = in.frame_id;
  out.stamp_s = in.stamp_s;
  out.points.resize(m);
  if (in.has_intensity()) out.intensities.resize(m);
  if (in.has_time()) out.time_offsets_s.resize(m);
  if (in.has_ring()) out.rings.resize(m);
  for (std::size_t v = 0; v < m; ++v) {
    const detail::VoxelAccumulator& a = acc_[v];
    const double inv = 1.0 / a.count;
    out.points[v] =
        Eigen::Vector3f(static_cast<float>(a.x * inv), static_cast<float>(a.y * inv), static_cast<float>(a.z * inv));
    if (in.has_intensity()) out.intensities[v] = static_cast<float>(a.intensity * inv);
    if (in.has_time()) out.time_offsets_s[v] = static_cast<float>(a.time * inv);
    if (in.has_ring()) out.rings[v] = in.rings[a.first];
  }
}

void VoxelGrid::filter(const PointCloud& in, PointCloud& out, const PassThroughTest* crop) {
  if (!in.is_consistent()) throw Error("voxel_downsample: the cloud's optional fields do not match its point count");
  if (&in == &out) throw Error("VoxelGrid::filter: the output cloud must not be the input cloud");
  acc_.clear();
  acc_.reserve(in.size() / 8);
  rebuild(std::max({kMinSlots, slots_.size(), std::bit_ceil(in.size() / 16)}));
  const bool with_i = in.has_intensity(), with_t = in.has_time();
  // Keys first (a sequential pass), so the table slot of a point a few ahead can be prefetched.
  constexpr std::uint64_t kSkip = ~std::uint64_t{0};
  const std::size_t n = in.size();
  keys_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3f& p = in.points[i];
    keys_[i] = (!p.allFinite() || (crop && !crop->keep(p))) ? kSkip : voxel_key(p, inv_leaf_);
  }
  // Neighbouring points of organised (depth image) clouds often share a voxel: remember the last.
  std::uint64_t last_key = kSkip;
  std::uint32_t v = 0;
  constexpr std::size_t kAhead = 8;
  for (std::size_t i = 0; i < n; ++i) {
    if (i + kAhead < n) __builtin_prefetch(&slots_[((keys_[i + kAhead] * 0x9E3779B97F4A7C15ull) >> shift_)]);
    const std::uint64_t key = keys_[i];
    if (key == kSkip) continue;
    if (key != last_key) {
      v = find_or_insert(key, static_cast<std::uint32_t>(i));
      last_key = key;
    }
    const Eigen::Vector3f& p = in.points[i];
    detail::VoxelAccumulator& a = acc_[v];
    a.x += p.x();
    a.y += p.y();
    a.z += p.z();
    if (with_i) a.intensity += in.intensities[i];
    if (with_t) a.time += in.time_offsets_s[i];
    ++a.count;
  }
  write_centroids(in, out);
}

PointCloud voxel_downsample(const PointCloud& in, const VoxelGridParams& params) {
  return VoxelGrid(params).filter(in);
}

}  // namespace bipednav::perception
