#include "bipednav/perception/decimation.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>

#include "bipednav/common/error.hpp"
#include "bipednav/common/simd4.hpp"

namespace bipednav::perception {
namespace {

// Squared range of a point; +inf for a point with a NaN or infinite coordinate.
inline float range2_or_inf(const Eigen::Vector3f& p) {
  const float r2 = p.squaredNorm();
  return r2 <= std::numeric_limits<float>::max() && p.allFinite() ? r2 : std::numeric_limits<float>::infinity();
}

// Compare-exchange without branches (the order of the ranges in a block is random: branches
// would mispredict half the time).
inline void sort2(float& a, std::uint32_t& ia, float& b, std::uint32_t& ib) {
  const bool swap = b < a;
  const float lo = swap ? b : a, hi = swap ? a : b;
  const std::uint32_t ilo = swap ? ib : ia, ihi = swap ? ia : ib;
  a = lo;
  b = hi;
  ia = ilo;
  ib = ihi;
}

using simd4::F4;
using simd4::I4;
using simd4::shuffle;

// range2_or_inf of four consecutive points (12 floats), lane-wise with the same operations:
// Eigen's squaredNorm of a Vector3f is x^2 + (y^2 + z^2) (tests/perception check it bit for bit).
inline F4 range2_or_inf4(const float* p) {
  const F4 a = simd4::load(p), b = simd4::load(p + 4),
           c = simd4::load(p + 8);  // x0 y0 z0 x1 | y1 z1 x2 y2 | z2 x3 y3 z3
  const F4 x = shuffle<0, 3, 4, 7>(a, shuffle<2, 3, 4, 5>(b, c));
  const F4 y = shuffle<0, 1, 4, 5>(shuffle<1, 4, 1, 4>(a, b), shuffle<3, 6, 3, 6>(b, c));
  const F4 z = shuffle<0, 1, 4, 5>(shuffle<2, 5, 2, 5>(a, b), shuffle<0, 3, 0, 3>(c, c));
  const F4 r2 = x * x + (y * y + z * z);
  const float inf = std::numeric_limits<float>::infinity();
  // NaN and infinite coordinates give a NaN or infinite r2, which fails the test as an overflow does.
  return r2 <= std::numeric_limits<float>::max() ? r2 : F4{inf, inf, inf, inf};
}

// sort2 on a vector of blocks at once (4 or 8 lanes).
template <class F, class I>
__attribute__((always_inline)) inline void sort2(F& a, I& ia, F& b, I& ib) {
  const I swap = b < a;
  const F lo = swap ? b : a, hi = swap ? a : b;
  const I ilo = swap ? ib : ia, ihi = swap ? ia : ib;
  a = lo;
  b = hi;
  ia = ilo;
  ib = ihi;
}

// decimate_by_2's step on L neighbouring blocks at once: r[k] lane j holds the squared range of
// pixel k (0, 1: top row; 2, 3: bottom row) of block j, the block of columns u + 2j, u + 2j + 1.
// Sorts each block by the 5-comparator network and emits its median when it is within r2_max.
// One template for the 4-lane loop and the 8-lane AVX2 loop (inlined into each, so the 8-lane
// instance compiles with the AVX2 target): the same comparisons and selections lane for lane.
template <class F, class I, int L>
__attribute__((always_inline)) inline void decimate_lanes(F (&r)[4], const Eigen::Vector3f* row0,
                                                          const Eigen::Vector3f* row1, std::size_t u, float r2_max,
                                                          Eigen::Vector3f*& o, DecimationCounts& n_out) {
  const float inf = std::numeric_limits<float>::infinity();
  const I zero{};
  I id[4] = {zero, zero + 1, zero + 2, zero + 3};
  const I n = -((r[0] < inf) + (r[1] < inf) + (r[2] < inf) + (r[3] < inf));
  std::int32_t any = 0, total = 0;
  for (int j = 0; j < L; ++j) any |= n[j], total += n[j];
  if (any == 0) return;
  n_out.finite += static_cast<std::size_t>(total);
  sort2(r[0], id[0], r[1], id[1]);
  sort2(r[2], id[2], r[3], id[3]);
  sort2(r[0], id[0], r[2], id[2]);
  sort2(r[1], id[1], r[3], id[3]);
  sort2(r[1], id[1], r[2], id[2]);
  const I three = n >= 3;  // (n - 1) / 2 is 1 for n = 3, 4 and 0 for n = 1, 2
  const F r_mid = three ? r[1] : r[0];
  const I id_mid = three ? id[1] : id[0];
  const I some = n > 0;
  const I keep = some & (r_mid <= r2_max);
  std::int32_t blocks = 0;
  for (int j = 0; j < L; ++j) blocks += some[j];
  n_out.blocks += static_cast<std::size_t>(-blocks);
  for (int j = 0; j < L; ++j) {
    if (!keep[j]) continue;
    const auto k = static_cast<std::uint32_t>(id_mid[j]);
    *o++ = (k < 2 ? row0 : row1)[u + 2 * static_cast<std::size_t>(j) + (k & 1u)];
  }
}

#if defined(__x86_64__) && defined(__GNUC__)
#define BIPEDNAV_DECIMATE_AVX2 1
// Eight blocks at a time where the CPU has AVX2 (checked at run time; the build targets baseline
// x86-64).
using DecimateF8 = float __attribute__((vector_size(32)));
using DecimateI8 = std::int32_t __attribute__((vector_size(32)));

bool decimate_cpu_has_avx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}

// Lanes 0-3 from lo, 4-7 from hi.
__attribute__((target("avx2"))) inline DecimateF8 decimate_join(F4 lo, F4 hi) {
  return __builtin_shufflevector(lo, hi, 0, 1, 2, 3, 4, 5, 6, 7);
}

// decimate_by_2's blocks eight at a time, columns u .. u + 15 of rows row0, row1, from u while 16
// columns are left; returns the first column not done.
__attribute__((target("avx2"))) std::size_t decimate_8_blocks_avx2(const Eigen::Vector3f* row0,
                                                                   const Eigen::Vector3f* row1, std::size_t u,
                                                                   std::size_t w, float r2_max, Eigen::Vector3f*& o,
                                                                   DecimationCounts& n_out) {
  for (; u + 16 <= w; u += 16) {
    const F4 a0 = range2_or_inf4(row0[u].data()), b0 = range2_or_inf4(row0[u + 4].data());
    const F4 a1 = range2_or_inf4(row1[u].data()), b1 = range2_or_inf4(row1[u + 4].data());
    const F4 c0 = range2_or_inf4(row0[u + 8].data()), d0 = range2_or_inf4(row0[u + 12].data());
    const F4 c1 = range2_or_inf4(row1[u + 8].data()), d1 = range2_or_inf4(row1[u + 12].data());
    DecimateF8 r[4] = {decimate_join(shuffle<0, 2, 4, 6>(a0, b0), shuffle<0, 2, 4, 6>(c0, d0)),
                       decimate_join(shuffle<1, 3, 5, 7>(a0, b0), shuffle<1, 3, 5, 7>(c0, d0)),
                       decimate_join(shuffle<0, 2, 4, 6>(a1, b1), shuffle<0, 2, 4, 6>(c1, d1)),
                       decimate_join(shuffle<1, 3, 5, 7>(a1, b1), shuffle<1, 3, 5, 7>(c1, d1))};
    decimate_lanes<DecimateF8, DecimateI8, 8>(r, row0, row1, u, r2_max, o, n_out);
  }
  return u;
}
#endif

// Factor 2, the common case: each 2 x 2 block is sorted by a 5-comparator network (the non-finite
// points, at +inf, sort last) and the lower median of its n finite points is element (n - 1) / 2.
// Four neighbouring blocks are sorted at once (lanes); leftover blocks of a row go one by one.
// The median is kept when its squared range is <= r2_max.
// The kept points are written from `dst` on (room for every block); `dst` ends past the last one.
DecimationCounts decimate_by_2(const Eigen::Vector3f* p, std::size_t w, std::size_t h, float r2_max,
                               Eigen::Vector3f*& dst) {
  DecimationCounts n_out;
  Eigen::Vector3f* o = dst;
  const float inf = std::numeric_limits<float>::infinity();
#if defined(BIPEDNAV_DECIMATE_AVX2)
  const bool avx2 = decimate_cpu_has_avx2();
#endif
  for (std::size_t v = 0; v + 2 <= h; v += 2) {
    const Eigen::Vector3f* row0 = p + v * w;
    const Eigen::Vector3f* row1 = row0 + w;
    std::size_t u = 0;
#if defined(BIPEDNAV_DECIMATE_AVX2)
    if (avx2) u = decimate_8_blocks_avx2(row0, row1, u, w, r2_max, o, n_out);
#endif
    for (; u + 8 <= w; u += 8) {
      const F4 a0 = range2_or_inf4(row0[u].data()), b0 = range2_or_inf4(row0[u + 4].data());
      const F4 a1 = range2_or_inf4(row1[u].data()), b1 = range2_or_inf4(row1[u + 4].data());
      F4 r[4] = {shuffle<0, 2, 4, 6>(a0, b0), shuffle<1, 3, 5, 7>(a0, b0), shuffle<0, 2, 4, 6>(a1, b1),
                 shuffle<1, 3, 5, 7>(a1, b1)};
      decimate_lanes<F4, I4, 4>(r, row0, row1, u, r2_max, o, n_out);
    }
    for (; u + 2 <= w; u += 2) {
      float r[4] = {range2_or_inf(row0[u]), range2_or_inf(row0[u + 1]), range2_or_inf(row1[u]),
                    range2_or_inf(row1[u + 1])};
      std::uint32_t id[4] = {0, 1, 2, 3};
      const int n = (r[0] < inf) + (r[1] < inf) + (r[2] < inf) + (r[3] < inf);
      if (n == 0) continue;
      n_out.finite += static_cast<std::size_t>(n);
      ++n_out.blocks;
      sort2(r[0], id[0], r[1], id[1]);
      sort2(r[2], id[2], r[3], id[3]);
      sort2(r[0], id[0], r[2], id[2]);
      sort2(r[1], id[1], r[3], id[3]);
      sort2(r[1], id[1], r[2], id[2]);
      if (!(r[(n - 1) / 2] <= r2_max)) continue;
      const std::uint32_t k = id[(n - 1) / 2];
      *o++ = (k < 2 ? row0 : row1)[u + (k & 1u)];
    }
  }
  dst = o;
  return n_out;
}

// Both entry points: the medians with squared range <= r2_max (+inf: all).
DecimationCounts decimate(const PointCloud& in, int width, int factor, float r2_max, PointCloud& out) {
  if (width < 1 || factor < 1 || factor > 8)
    throw Error("decimate_depth: width must be >= 1 and factor in [1, 8] (got " + std::to_string(width) + ", " +
                std::to_string(factor) + ")");
  const auto w = static_cast<std::size_t>(width), k = static_cast<std::size_t>(factor);
  if (in.size() % w != 0)
    throw Error("decimate_depth: " + std::to_string(in.size()) + " points are not whole rows of " +
                std::to_string(width));
  const std::size_t h = in.size() / w;
  out.clear();
  out.frame_id = in.frame_id;
  out.stamp_s = in.stamp_s;
  out.points.reserve((w / k) * (h / k));
  const Eigen::Vector3f* p = in.points.data();
  DecimationCounts n;
  if (k == 2) {
    out.points.resize((w / 2) * (h / 2));  // no-op constructors; shrunk to the points written
    Eigen::Vector3f* end = out.points.data();
    n = decimate_by_2(p, w, h, r2_max, end);
    out.points.resize(static_cast<std::size_t>(end - out.points.data()));
  }
  std::array<std::pair<float, std::uint32_t>, 64> block{};  // (squared range, index) of the finite points
  for (std::size_t bv = 0; k != 2 && bv + k <= h; bv += k)
    for (std::size_t bu = 0; bu + k <= w; bu += k) {
      std::size_t m = 0;
      for (std::size_t v = bv; v < bv + k; ++v)
        for (std::size_t u = bu; u < bu + k; ++u) {
          const std::size_t i = v * w + u;
          const float r2 = range2_or_inf(p[i]);
          if (r2 < std::numeric_limits<float>::infinity()) block[m++] = {r2, static_cast<std::uint32_t>(i)};
        }
      n.finite += m;
      if (m == 0) continue;
      ++n.blocks;
      const auto mid = block.begin() + static_cast<std::ptrdiff_t>((m - 1) / 2);
      std::nth_element(block.begin(), mid, block.begin() + static_cast<std::ptrdiff_t>(m));
      if (mid->first <= r2_max) out.points.push_back(p[mid->second]);
    }
  // Points of the dropped edge rows and columns still count as received.
  for (std::size_t v = 0; v < h; ++v)
    for (std::size_t u = (v < (h / k) * k ? (w / k) * k : 0); u < w; ++u) n.finite += p[v * w + u].allFinite() ? 1 : 0;
  return n;
}

}  // namespace

std::size_t decimate_depth(const PointCloud& in, int width, int factor, PointCloud& out) {
  return decimate(in, width, factor, std::numeric_limits<float>::infinity(), out).finite;
}

DecimationCounts decimate_depth_within(const PointCloud& in, int width, int factor, double max_range_m,
                                       PointCloud& out) {
  if (!(max_range_m > 0.0))
    throw Error("decimate_depth_within: max_range_m must be > 0 (got " + std::to_string(max_range_m) + ")");
  // As PassThroughTest: the square in double, then float (an infinite limit stays infinite).
  return decimate(in, width, factor, static_cast<float>(max_range_m * max_range_m), out);
}

}  // namespace bipednav::perception
