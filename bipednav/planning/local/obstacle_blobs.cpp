#include "bipednav/planning/local/obstacle_blobs.hpp"

#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <unordered_map>

#include "bipednav/common/error.hpp"

namespace bipednav::planning::local {

namespace {

std::uint64_t cell_key(long x, long y) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(x)) << 32) |
         static_cast<std::uint64_t>(static_cast<std::uint32_t>(y));
}

// cluster_blobs' binning of the points in range, four at a time: the same finite test, squared
// distance, quotient and floor as the scalar loop (IEEE division, subtraction, product and sum
// without contraction, and floor are exact operations: the lanes give the scalar's bits). A block
// whose kept bins do not fit an int32 is left to the scalar loop (returns its index).
#define BIPEDNAV_BLOB_AVX2 __attribute__((target("avx2")))
BIPEDNAV_BLOB_AVX2 std::size_t blob_bins_avx2(const Eigen::Vector2d* points, std::size_t n,
                                              const Eigen::Vector2d& center, double r2max, double cell, long* bx,
                                              long* by, std::size_t* kept, std::size_t& m) {
  static_assert(sizeof(Eigen::Vector2d) == 2 * sizeof(double));
  const __m256d cx = _mm256_set1_pd(center.x()), cy = _mm256_set1_pd(center.y());
  const __m256d r2 = _mm256_set1_pd(r2max), c = _mm256_set1_pd(cell), zero = _mm256_setzero_pd();
  const __m256d lo = _mm256_set1_pd(-2147483648.0), hi = _mm256_set1_pd(2147483647.0);
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    const double* d = points[i].data();
    const __m256d a = _mm256_loadu_pd(d), b = _mm256_loadu_pd(d + 4);         // x0 y0 x1 y1 | x2 y2 x3 y3
    const __m256d x = _mm256_permute4x64_pd(_mm256_unpacklo_pd(a, b), 0xD8);  // x0 x1 x2 x3
    const __m256d y = _mm256_permute4x64_pd(_mm256_unpackhi_pd(a, b), 0xD8);
    // p.allFinite(): x - x and y - y are 0 (NaN for an infinity or a NaN).
    const __m256d finite = _mm256_and_pd(_mm256_cmp_pd(_mm256_sub_pd(x, x), zero, _CMP_EQ_OQ),
                                         _mm256_cmp_pd(_mm256_sub_pd(y, y), zero, _CMP_EQ_OQ));
    const __m256d dx = _mm256_sub_pd(x, cx), dy = _mm256_sub_pd(y, cy);
    const __m256d s = _mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy));
    const int keep = _mm256_movemask_pd(_mm256_and_pd(finite, _mm256_cmp_pd(s, r2, _CMP_NGT_UQ)));  // !(s > r2max)
    if (keep == 0) continue;
    const __m256d qx = _mm256_floor_pd(_mm256_div_pd(x, c)), qy = _mm256_floor_pd(_mm256_div_pd(y, c));
    const __m256d fits =
        _mm256_and_pd(_mm256_and_pd(_mm256_cmp_pd(qx, lo, _CMP_GE_OQ), _mm256_cmp_pd(qx, hi, _CMP_LE_OQ)),
                      _mm256_and_pd(_mm256_cmp_pd(qy, lo, _CMP_GE_OQ), _mm256_cmp_pd(qy, hi, _CMP_LE_OQ)));
    if ((_mm256_movemask_pd(fits) & keep) != keep) return i;
    alignas(16) std::int32_t xi[4], yi[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(xi), _mm256_cvttpd_epi32(qx));
    _mm_store_si128(reinterpret_cast<__m128i*>(yi), _mm256_cvttpd_epi32(qy));
    for (int l = 0; l < 4; ++l) {
      if (!(keep & (1 << l))) continue;
      bx[m] = xi[l], by[m] = yi[l], kept[m] = i + static_cast<std::size_t>(l);
      ++m;
    }
  }
  return i;
}

bool blob_cpu_has_avx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}

// The bins of the points in range, in point order.
void bin_points(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& center, double cell, double r2max,
                BlobScratch& w) {
  std::vector<long>&bx = w.bx, &by = w.by;
  std::vector<std::size_t>& in_range = w.in_range;
  bx.resize(points.size());
  by.resize(points.size());
  in_range.resize(points.size());
  std::size_t m = 0, first = 0;
  if (blob_cpu_has_avx2())
    first = blob_bins_avx2(points.data(), points.size(), center, r2max, cell, bx.data(), by.data(), in_range.data(), m);
  for (std::size_t i = first; i < points.size(); ++i) {
    const Eigen::Vector2d& p = points[i];
    if (!p.allFinite() || (p - center).squaredNorm() > r2max) continue;
    bx[m] = static_cast<long>(std::floor(p.x() / cell)), by[m] = static_cast<long>(std::floor(p.y() / cell));
    in_range[m++] = i;
  }
  bx.resize(m);
  by.resize(m);
  in_range.resize(m);
}

// Where to find the cells of the occupied bins (index_cells).
struct CellIndex {
  long x_lo = 0, x_hi = -1, y_lo = 0, y_hi = -1;
  bool dense = false;
  std::size_t H = 0;
  const std::vector<std::int32_t>* grid = nullptr;  // dense
  std::unordered_map<std::uint64_t, std::size_t> cell_of;

  // The cell at bin (x, y), or -1.
  std::int64_t find(long x, long y) const {
    if (dense) {
      if (x < x_lo || x > x_hi || y < y_lo || y > y_hi) return -1;
      return (*grid)[static_cast<std::size_t>(x - x_lo) * H + static_cast<std::size_t>(y - y_lo)];
    }
    const auto it = cell_of.find(cell_key(x, y));
    return it == cell_of.end() ? -1 : static_cast<std::int64_t>(it->second);
  }
};

// index_cells over a small window: a counting sort of the bins.
void index_dense(BlobScratch& w, CellIndex& index) {
  const std::vector<long>&bx = w.bx, &by = w.by;
  const std::vector<std::size_t>& in_range = w.in_range;
  std::vector<std::size_t>& order = w.order;
  std::vector<std::pair<std::size_t, std::size_t>>& cells = w.cells;
  std::vector<std::pair<long, long>>& cell_xy = w.cell_xy;
  std::vector<std::int32_t>& grid = w.grid;
  const long x_lo = index.x_lo, y_lo = index.y_lo;
  const std::size_t H = index.H;
  const std::size_t W = static_cast<std::size_t>(index.x_hi - x_lo + 1);
  std::vector<std::uint32_t>& start = w.start;
  start.assign(W * H + 1, 0);
  const auto bin = [&](std::size_t k) {
    return static_cast<std::size_t>(bx[k] - x_lo) * H + static_cast<std::size_t>(by[k] - y_lo);
  };
  for (std::size_t k = 0; k < in_range.size(); ++k) ++start[bin(k) + 1];
  grid.assign(W * H, -1);
  for (std::size_t b = 0; b < W * H; ++b) {
    if (start[b + 1] > 0) {
      grid[b] = static_cast<std::int32_t>(cells.size());
      cells.emplace_back(start[b], start[b] + start[b + 1]);
      cell_xy.emplace_back(x_lo + static_cast<long>(b / H), y_lo + static_cast<long>(b % H));
    }
    start[b + 1] += start[b];
  }
  for (std::size_t k = 0; k < in_range.size(); ++k) order[start[bin(k)]++] = in_range[k];
}

// index_cells over a window too large for index_dense: sorted bins and a hash of them.
void index_hashed(BlobScratch& w, CellIndex& index) {
  std::vector<std::tuple<long, long, std::size_t>> binned(w.in_range.size());
  for (std::size_t k = 0; k < w.in_range.size(); ++k) binned[k] = {w.bx[k], w.by[k], w.in_range[k]};
  std::sort(binned.begin(), binned.end());
  for (std::size_t i = 0; i < binned.size();) {
    std::size_t j = i;
    while (j < binned.size() && std::get<0>(binned[j]) == std::get<0>(binned[i]) &&
           std::get<1>(binned[j]) == std::get<1>(binned[i]))
      ++j;
    index.cell_of.emplace(cell_key(std::get<0>(binned[i]), std::get<1>(binned[i])), w.cells.size());
    w.cells.emplace_back(i, j);
    w.cell_xy.emplace_back(std::get<0>(binned[i]), std::get<1>(binned[i]));
    i = j;
  }
  for (std::size_t k = 0; k < binned.size(); ++k) w.order[k] = std::get<2>(binned[k]);
}

// Cells in a fixed order, (x, y) ascending, each a [begin, end) range of `order` (point indices,
// ascending within a cell). The bins span a small window (max_range_m around the robot): a
// counting sort over it; a hash of the bins when the window is too large for that.
void index_cells(BlobScratch& w, CellIndex& index) {
  const std::vector<long>&bx = w.bx, &by = w.by;
  const std::vector<std::size_t>& in_range = w.in_range;
  w.order.resize(in_range.size());
  const std::size_t m = in_range.size();
  long x_lo = 0, x_hi = -1, y_lo = 0, y_hi = -1;
  if (m > 0) {
    x_lo = x_hi = bx[0], y_lo = y_hi = by[0];
    for (std::size_t k = 1; k < m; ++k)
      x_lo = std::min(x_lo, bx[k]), x_hi = std::max(x_hi, bx[k]), y_lo = std::min(y_lo, by[k]),
      y_hi = std::max(y_hi, by[k]);
  }
  index.x_lo = x_lo, index.x_hi = x_hi, index.y_lo = y_lo, index.y_hi = y_hi;
  w.cells.clear();
  w.cell_xy.clear();
  const auto span_x = static_cast<unsigned long>(x_hi - x_lo), span_y = static_cast<unsigned long>(y_hi - y_lo);
  const std::size_t grid_limit = std::max<std::size_t>(1 << 16, 8 * in_range.size());
  index.dense = span_x < grid_limit && span_y < grid_limit && (span_x + 1) * (span_y + 1) <= grid_limit;
  index.H = static_cast<std::size_t>(span_y + 1);
  index.grid = &w.grid;  // dense: cell index per bin, -1 when empty
  if (index.dense)
    index_dense(w, index);
  else
    index_hashed(w, index);
}

// The 8-connected cells of cell c0 (not seen yet) into BlobScratch::members, marking them seen.
void collect_cells(std::size_t c0, const CellIndex& index, BlobScratch& w) {
  std::vector<char>& seen = w.seen;
  std::vector<std::size_t>&stack = w.stack, &members = w.members;
  seen[c0] = 1;
  stack.assign(1, c0);
  members.clear();
  while (!stack.empty()) {
    const std::size_t c = stack.back();
    stack.pop_back();
    members.push_back(c);
    const auto [cx, cy] = w.cell_xy[c];
    for (long dy = -1; dy <= 1; ++dy) {
      for (long dx = -1; dx <= 1; ++dx) {
        const std::int64_t n = index.find(cx + dx, cy + dy);
        if (n >= 0 && !seen[static_cast<std::size_t>(n)])
          seen[static_cast<std::size_t>(n)] = 1, stack.push_back(static_cast<std::size_t>(n));
      }
    }
  }
}

// The blob of the points of BlobScratch::members.
Blob blob_of(const std::vector<Eigen::Vector2d>& points, const std::vector<double>& heights, const BlobScratch& w) {
  const auto& cells = w.cells;
  const auto& order = w.order;
  Blob b;
  for (const std::size_t c : w.members) {
    for (std::size_t k = cells[c].first; k < cells[c].second; ++k) {
      const std::size_t i = order[k];
      b.centroid += points[i];
      if (!heights.empty() && std::isfinite(heights[i])) b.top_m = std::max(b.top_m, heights[i]);
    }
    b.points += static_cast<int>(cells[c].second - cells[c].first);
  }
  b.centroid /= static_cast<double>(b.points);
  // The largest distance is the square root of the largest squared distance (the rounded square
  // root is monotonic): one square root per blob.
  double r2 = 0.0;
  for (const std::size_t c : w.members) {
    for (std::size_t k = cells[c].first; k < cells[c].second; ++k)
      r2 = std::max(r2, (points[order[k]] - b.centroid).squaredNorm());
  }
  b.radius_m = std::max(b.radius_m, std::sqrt(r2));
  return b;
}

}  // namespace

std::vector<Blob> cluster_blobs(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& center,
                                const MovingObstacleParams& params, const std::vector<double>& heights,
                                BlobScratch* scratch) {
  require(heights.empty() || heights.size() == points.size(), "cluster_blobs heights",
          "empty or one per point (" + std::to_string(points.size()) + "), got " + std::to_string(heights.size()));
  std::vector<Blob> out;
  const double cell = params.cluster_cell_m;
  const double r2max = params.max_range_m * params.max_range_m;
  BlobScratch own;
  BlobScratch& w = scratch != nullptr ? *scratch : own;
  bin_points(points, center, cell, r2max, w);
  if (w.in_range.empty()) return out;
  CellIndex index;
  index_cells(w, index);
  w.seen.assign(w.cells.size(), 0);
  for (std::size_t c0 = 0; c0 < w.cells.size(); ++c0) {
    if (w.seen[c0]) continue;
    collect_cells(c0, index, w);
    const Blob b = blob_of(points, heights, w);
    if (b.points < params.min_points || b.radius_m > params.max_blob_radius_m) continue;
    out.push_back(b);
  }
  return out;
}

}  // namespace bipednav::planning::local
