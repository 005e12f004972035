#include "bipednav/perception/decimation.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <string>
#include <utility>

#include "bipednav/common/error.hpp"

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

// Factor 2, the common case: each 2 x 2 block is sorted by a 5-comparator network (the non-finite
// points, at +inf, sort last) and the lower median of its n finite points is element (n - 1) / 2.
std::size_t decimate_by_2(const Eigen::Vector3f* p, std::size_t w, std::size_t h, PointCloud& out) {
  std::size_t finite = 0;
  for (std::size_t v = 0; v + 2 <= h; v += 2) {
    const Eigen::Vector3f* row0 = p + v * w;
    const Eigen::Vector3f* row1 = row0 + w;
    for (std::size_t u = 0; u + 2 <= w; u += 2) {
      float r[4] = {range2_or_inf(row0[u]), range2_or_inf(row0[u + 1]), range2_or_inf(row1[u]),
                    range2_or_inf(row1[u + 1])};
      std::uint32_t id[4] = {0, 1, 2, 3};
      const int n = (r[0] < std::numeric_limits<float>::infinity()) + (r[1] < std::numeric_limits<float>::infinity()) +
                    (r[2] < std::numeric_limits<float>::infinity()) + (r[3] < std::numeric_limits<float>::infinity());
      if (n == 0) continue;
      finite += static_cast<std::size_t>(n);
      sort2(r[0], id[0], r[1], id[1]);
      sort2(r[2], id[2], r[3], id[3]);
      sort2(r[0], id[0], r[2], id[2]);
      sort2(r[1], id[1], r[3], id[3]);
      sort2(r[1], id[1], r[2], id[2]);
      const std::uint32_t k = id[(n - 1) / 2];
      out.points.push_back((k < 2 ? row0 : row1)[u + (k & 1u)]);
    }
  }
  return finite;
}

}  // namespace

std::size_t decimate_depth(const PointCloud& in, int width, int factor, PointCloud& out) {
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
  std::size_t finite = 0;
  if (k == 2) finite = decimate_by_2(p, w, h, out);
  std::array<std::pair<float, std::uint32_t>, 64> block{};  // (squared range, index) of the finite points
  for (std::size_t bv = 0; k != 2 && bv + k <= h; bv += k)
    for (std::size_t bu = 0; bu + k <= w; bu += k) {
      std::size_t n = 0;
      for (std::size_t v = bv; v < bv + k; ++v)
        for (std::size_t u = bu; u < bu + k; ++u) {
          const std::size_t i = v * w + u;
          const float r2 = range2_or_inf(p[i]);
          if (r2 < std::numeric_limits<float>::infinity()) block[n++] = {r2, static_cast<std::uint32_t>(i)};
        }
      finite += n;
      if (n == 0) continue;
      const auto mid = block.begin() + static_cast<std::ptrdiff_t>((n - 1) / 2);
      std::nth_element(block.begin(), mid, block.begin() + static_cast<std::ptrdiff_t>(n));
      out.points.push_back(p[mid->second]);
    }
  // Points of the dropped edge rows and columns still count as received.
  for (std::size_t v = 0; v < h; ++v)
    for (std::size_t u = (v < (h / k) * k ? (w / k) * k : 0); u < w; ++u) finite += p[v * w + u].allFinite() ? 1 : 0;
  return finite;
}

}  // namespace bipednav::perception
