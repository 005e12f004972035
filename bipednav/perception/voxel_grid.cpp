#include "bipednav/perception/voxel_grid.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>

#include "bipednav/common/error.hpp"
#include "bipednav/common/xyz4.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define BIPEDNAV_VOXEL_AVX2 1
#endif

namespace bipednav::perception {

void VoxelGridParams::validate() const {
  for (int a = 0; a < 3; ++a)
    require(std::isfinite(leaf_size_m[a]) && leaf_size_m[a] > 0.0, "leaf_size_m", "three finite sizes > 0 m");
}

namespace {

constexpr int kAxisBits = 21;
constexpr std::int32_t kAxisHalf = std::int32_t{1} << (kAxisBits - 1);
constexpr double kHalf = kAxisHalf;
constexpr std::uint32_t kEmpty = 0xffffffffu;
constexpr std::size_t kMinSlots = 4096;
constexpr std::uint64_t kHashMul = 0x9E3779B97F4A7C15ull;
using detail::kSkipKey;

static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float), "points are read as interleaved floats");

// The key of one point, and whether it is finite / in the key range. floor() by truncation and a
// fix-up (baseline x86-64 has no SSE4.1 round instruction); the SIMD path computes the same.
inline std::uint64_t scalar_key(const float* p, const Eigen::Vector3d& inv_leaf, bool& finite, bool& in_range) {
  std::uint64_t key = 0;
  finite = in_range = true;
  for (int a = 0; a < 3; ++a) {
    const double s = static_cast<double>(p[a]) * inv_leaf[a];
    finite &= s - s == 0.0;
    in_range &= s >= -kHalf && s < kHalf;
    const double c = in_range ? s : 0.0;
    const auto t = static_cast<std::int32_t>(c);
    key = (key << kAxisBits) | static_cast<std::uint32_t>(t - (c < t ? 1 : 0) + kAxisHalf);
  }
  return in_range ? key : kSkipKey;
}

#if defined(__SSE2__)
// Two points per step, in double like the scalar path.
inline __m128i axis_keys(__m128d s, __m128d in) {
  s = _mm_and_pd(s, in);  // out of range or NaN -> 0 (its key is replaced anyway)
  __m128i t = _mm_cvttpd_epi32(s);
  const __m128d below = _mm_cmplt_pd(s, _mm_cvtepi32_pd(t));  // truncated up: subtract one
  t = _mm_add_epi32(t, _mm_shuffle_epi32(_mm_castpd_si128(below), _MM_SHUFFLE(3, 3, 2, 0)));
  return _mm_unpacklo_epi32(_mm_add_epi32(t, _mm_set1_epi32(kAxisHalf)), _mm_setzero_si128());
}

inline __m128d in_range(__m128d s) {
  return _mm_and_pd(_mm_cmpge_pd(s, _mm_set1_pd(-kHalf)), _mm_cmplt_pd(s, _mm_set1_pd(kHalf)));
}

inline __m128d finite(__m128d s) { return _mm_cmpeq_pd(_mm_sub_pd(s, s), _mm_setzero_pd()); }

std::size_t simd_keys(const float* xyz, std::size_t n, const Eigen::Vector3d& inv_leaf, std::uint64_t* keys, bool& ok) {
  const __m128d lx = _mm_set1_pd(inv_leaf[0]), ly = _mm_set1_pd(inv_leaf[1]), lz = _mm_set1_pd(inv_leaf[2]);
  __m128d bad = _mm_setzero_pd();
  std::size_t i = 0;
  for (; i + 2 <= n; i += 2) {
    const float* p = xyz + 3 * i;  // x0 y0 | z0 x1 | y1 z1
    const __m128d a = _mm_cvtps_pd(_mm_castpd_ps(_mm_load_sd(reinterpret_cast<const double*>(p))));
    const __m128d b = _mm_cvtps_pd(_mm_castpd_ps(_mm_load_sd(reinterpret_cast<const double*>(p + 2))));
    const __m128d c = _mm_cvtps_pd(_mm_castpd_ps(_mm_load_sd(reinterpret_cast<const double*>(p + 4))));
    const __m128d sx = _mm_mul_pd(_mm_shuffle_pd(a, b, 0b10), lx);
    const __m128d sy = _mm_mul_pd(_mm_shuffle_pd(a, c, 0b01), ly);
    const __m128d sz = _mm_mul_pd(_mm_shuffle_pd(b, c, 0b10), lz);
    const __m128d in = _mm_and_pd(_mm_and_pd(in_range(sx), in_range(sy)), in_range(sz));
    bad = _mm_or_pd(bad, _mm_andnot_pd(in, _mm_and_pd(_mm_and_pd(finite(sx), finite(sy)), finite(sz))));
    __m128i key =
        _mm_or_si128(_mm_slli_epi64(axis_keys(sx, in), 2 * kAxisBits), _mm_slli_epi64(axis_keys(sy, in), kAxisBits));
    key = _mm_or_si128(_mm_or_si128(key, axis_keys(sz, in)), _mm_xor_si128(_mm_castpd_si128(in), _mm_set1_epi32(-1)));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(keys + i), key);
  }
  ok = _mm_movemask_pd(bad) == 0;
  return i;
}
#endif

#if defined(BIPEDNAV_VOXEL_AVX2)
// Four points per step where the CPU has AVX2 (picked at run time; the build targets baseline
// x86-64): the same products in double, floor by the round instruction.
#define BIPEDNAV_AVX2 __attribute__((target("avx2")))
BIPEDNAV_AVX2 inline __m256d in_range4(__m256d s) {
  return _mm256_and_pd(_mm256_cmp_pd(s, _mm256_set1_pd(-kHalf), _CMP_GE_OQ),
                       _mm256_cmp_pd(s, _mm256_set1_pd(kHalf), _CMP_LT_OQ));
}

BIPEDNAV_AVX2 inline __m256d finite4(__m256d s) {
  return _mm256_cmp_pd(_mm256_sub_pd(s, s), _mm256_setzero_pd(), _CMP_EQ_OQ);
}

BIPEDNAV_AVX2 inline __m256i axis_keys4(__m256d s, __m256d in) {
  const __m128i t = _mm256_cvttpd_epi32(_mm256_floor_pd(_mm256_and_pd(s, in)));
  return _mm256_cvtepu32_epi64(_mm_add_epi32(t, _mm_set1_epi32(kAxisHalf)));
}

BIPEDNAV_AVX2 std::size_t avx2_keys(const float* xyz, std::size_t n, const Eigen::Vector3d& inv_leaf,
                                    std::uint64_t* keys, bool& ok) {
  const __m256d lx = _mm256_set1_pd(inv_leaf[0]), ly = _mm256_set1_pd(inv_leaf[1]), lz = _mm256_set1_pd(inv_leaf[2]);
  __m256d bad = _mm256_setzero_pd();
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    const auto [x, y, z] = xyz4::load(xyz + 3 * i);
    const __m256d sx = _mm256_mul_pd(_mm256_cvtps_pd(x), lx);
    const __m256d sy = _mm256_mul_pd(_mm256_cvtps_pd(y), ly);
    const __m256d sz = _mm256_mul_pd(_mm256_cvtps_pd(z), lz);
    const __m256d in = _mm256_and_pd(_mm256_and_pd(in_range4(sx), in_range4(sy)), in_range4(sz));
    bad = _mm256_or_pd(bad, _mm256_andnot_pd(in, _mm256_and_pd(_mm256_and_pd(finite4(sx), finite4(sy)), finite4(sz))));
    __m256i key = _mm256_or_si256(_mm256_slli_epi64(axis_keys4(sx, in), 2 * kAxisBits),
                                  _mm256_slli_epi64(axis_keys4(sy, in), kAxisBits));
    key = _mm256_or_si256(_mm256_or_si256(key, axis_keys4(sz, in)),
                          _mm256_xor_si256(_mm256_castpd_si256(in), _mm256_set1_epi32(-1)));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(keys + i), key);
  }
  ok = _mm256_movemask_pd(bad) == 0;
  return i;
}
#endif

}  // namespace

bool detail::voxel_keys(const float* xyz, std::size_t n, const Eigen::Vector3d& inv_leaf, std::uint64_t* keys) {
  bool ok = true;
  std::size_t i = 0;
#if defined(BIPEDNAV_VOXEL_AVX2)
  if (__builtin_cpu_supports("avx2"))
    i = avx2_keys(xyz, n, inv_leaf, keys, ok);
  else
#endif
#if defined(__SSE2__)
    i = simd_keys(xyz, n, inv_leaf, keys, ok);
#endif
  for (; i < n; ++i) {
    bool finite = false, in_range = false;
    keys[i] = scalar_key(xyz + 3 * i, inv_leaf, finite, in_range);
    ok &= in_range || !finite;
  }
  return ok;
}

VoxelGrid::VoxelGrid(const VoxelGridParams& params) : params_(params) {
  params_.validate();
  inv_leaf_ = params_.leaf_size_m.cwiseInverse();
}

// A slot holds only the voxel's index (4 bytes, so the table stays in cache); the key is compared
// in the dense per-voxel key array. The table doubles at half load.
inline std::uint32_t VoxelGrid::find_or_insert(std::uint64_t key, std::uint32_t point) {
  std::size_t s = static_cast<std::size_t>((key * kHashMul) >> shift_);
  while (true) {
    const std::uint32_t v = slots_[s];
    if (v == kEmpty) break;
    if (voxel_keys_[v] == key) return v;
    s = (s + 1) & mask_;
  }
  const auto v = static_cast<std::uint32_t>(voxel_keys_.size());
  voxel_keys_.push_back(key);
  sums_.push_back({0.0, 0.0, 0.0, 0, point});
  if (with_extra_) extra_sums_.push_back({0.0, 0.0});
  slots_[s] = v;
  if (2 * voxel_keys_.size() > slots_.size()) rebuild(2 * slots_.size());
  return v;
}

void VoxelGrid::rebuild(std::size_t capacity) {
  slots_.assign(capacity, kEmpty);
  mask_ = capacity - 1;
  shift_ = 64 - std::countr_zero(capacity);
  for (std::size_t v = 0; v < voxel_keys_.size(); ++v) {
    std::size_t s = static_cast<std::size_t>((voxel_keys_[v] * kHashMul) >> shift_);
    while (slots_[s] != kEmpty) s = (s + 1) & mask_;
    slots_[s] = static_cast<std::uint32_t>(v);
  }
}

// The rare path of a block with a finite point beyond the key range: the error is raised only when
// that point would be kept.
void VoxelGrid::check_range(const PointCloud& in, std::size_t begin, std::size_t end,
                            const PassThroughTest* crop) const {
  for (std::size_t i = begin; i < end; ++i) {
    const Eigen::Vector3f& p = in.points[i];
    bool finite = false, in_range = false;
    scalar_key(p.data(), inv_leaf_, finite, in_range);
    if (finite && !in_range && (!crop || crop->keep(p)))
      throw Error("voxel_downsample: point (" + std::to_string(p.x()) + ", " + std::to_string(p.y()) + ", " +
                  std::to_string(p.z()) +
                  ") is too far from the origin for the leaf size (key overflow); increase leaf_size_m");
  }
}

// Keys are computed a block at a time (vectorised, into a buffer that stays in L1), then the points
// are grouped. Neighbouring points of organised (depth image) clouds often share a voxel, so a run
// of equal keys is summed in registers and added to its voxel once; runs of dropped points are
// summed too (branch-free) and thrown away. Sums of floats in double are exact here, so the order
// of the additions does not change the centroids.
template <bool kExtra>
void VoxelGrid::accumulate(const PointCloud& in, std::size_t begin, std::size_t end) {
  const float* xyz = in.points.front().data();
  const bool with_i = in.has_intensity(), with_t = in.has_time();
  std::uint64_t run_key = kSkipKey;
  std::uint32_t v = 0, count = 0;
  double sx = 0.0, sy = 0.0, sz = 0.0, si = 0.0, st = 0.0;
  const auto flush = [&] {
    if (run_key == kSkipKey) return;
    detail::VoxelSum& s = sums_[v];
    s.x += sx;
    s.y += sy;
    s.z += sz;
    s.count += count;
    if constexpr (kExtra) {
      extra_sums_[v][0] += si;
      extra_sums_[v][1] += st;
    }
  };
  constexpr std::size_t kAhead = 8;
  for (std::size_t i = begin; i < end; ++i) {
    const std::uint64_t key = block_keys_[i - begin];
    // The slot of a key a few points ahead (stale keys past the end only cost a useless prefetch).
    if (i - begin + kAhead < block_keys_.size())
      __builtin_prefetch(&slots_[(block_keys_[i - begin + kAhead] * kHashMul) >> shift_]);
    if (key != run_key) {
      flush();
      run_key = key;
      sx = sy = sz = si = st = 0.0;
      count = 0;
      if (key != kSkipKey) v = find_or_insert(key, static_cast<std::uint32_t>(i));
    }
    const float* p = xyz + 3 * i;
    sx += p[0];
    sy += p[1];
    sz += p[2];
    ++count;
    if constexpr (kExtra) {
      si += with_i ? in.intensities[i] : 0.0f;
      st += with_t ? in.time_offsets_s[i] : 0.0f;
    }
  }
  flush();
}

void VoxelGrid::write_centroids(const PointCloud& in, PointCloud& out) const {
  const std::size_t m = sums_.size();
  out.clear();
  out.frame_id = in.frame_id;
  out.stamp_s = in.stamp_s;
  out.points.resize(m);
  if (in.has_intensity()) out.intensities.resize(m);
  if (in.has_time()) out.time_offsets_s.resize(m);
  if (in.has_ring()) out.rings.resize(m);
  for (std::size_t v = 0; v < m; ++v) {
    const detail::VoxelSum& a = sums_[v];
    const double inv = 1.0 / a.count;
    out.points[v] =
        Eigen::Vector3f(static_cast<float>(a.x * inv), static_cast<float>(a.y * inv), static_cast<float>(a.z * inv));
    if (in.has_intensity()) out.intensities[v] = static_cast<float>(extra_sums_[v][0] * inv);
    if (in.has_time()) out.time_offsets_s[v] = static_cast<float>(extra_sums_[v][1] * inv);
    if (in.has_ring()) out.rings[v] = in.rings[a.first];
  }
}

void VoxelGrid::filter(const PointCloud& in, PointCloud& out, const PassThroughTest* crop) {
  if (!in.is_consistent()) throw Error("voxel_downsample: the cloud's optional fields do not match its point count");
  if (&in == &out) throw Error("VoxelGrid::filter: the output cloud must not be the input cloud");
  // Sized for the previous call's voxel count (a pipeline's clouds change slowly) or a sixteenth
  // of the points, at most half full.
  const std::size_t expected = std::max(voxel_keys_.size(), in.size() / 16);
  voxel_keys_.clear();
  sums_.clear();
  extra_sums_.clear();
  with_extra_ = in.has_intensity() || in.has_time();
  rebuild(std::max(kMinSlots, std::bit_ceil(2 * expected)));
  const std::size_t n = in.size();
  for (std::size_t begin = 0; begin < n; begin += block_keys_.size()) {
    const std::size_t end = std::min(n, begin + block_keys_.size());
    if (!detail::voxel_keys(in.points[begin].data(), end - begin, inv_leaf_, block_keys_.data()))
      check_range(in, begin, end, crop);
    if (crop)
      for (std::size_t i = begin; i < end; ++i)
        if (!crop->keep(in.points[i])) block_keys_[i - begin] = kSkipKey;
    with_extra_ ? accumulate<true>(in, begin, end) : accumulate<false>(in, begin, end);
  }
  write_centroids(in, out);
}

PointCloud voxel_downsample(const PointCloud& in, const VoxelGridParams& params) {
  return VoxelGrid(params).filter(in);
}

}  // namespace bipednav::perception
