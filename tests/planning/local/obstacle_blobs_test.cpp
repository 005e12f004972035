#include "bipednav/planning/local/obstacle_blobs.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <tuple>
#include <unordered_map>
#include <vector>

#include "bipednav/common/error.hpp"
#include "moving_obstacle_test_utils.hpp"

namespace bipednav::planning::local {

TEST(MovingObstacles, ClusterBlobsSeparatesSmallBlobsAndDropsWalls) {
  std::vector<Eigen::Vector2d> pts;
  add_square(pts, {1.0, 1.0}, 0.15, 0);
  add_square(pts, {2.0, -1.0}, 0.4, 1);
  add_wall(pts, -3.0, 3.0, 2.5);         // a wall: too large to be a blob
  pts.emplace_back(-1.5, -1.5);          // a single return: noise
  pts.emplace_back(std::nan(""), 0.0);   // skipped
  add_square(pts, {9.0, 0.0}, 0.15, 2);  // out of range
  const auto blobs = cluster_blobs(pts, {0.0, 0.0}, enabled_tracking());
  ASSERT_EQ(blobs.size(), 2u);
  EXPECT_NEAR(blobs[0].centroid.x(), 1.0, 0.02);
  EXPECT_NEAR(blobs[0].centroid.y(), 1.0, 0.02);
  EXPECT_NEAR(blobs[1].centroid.x(), 2.0, 0.02);
  EXPECT_NEAR(blobs[1].centroid.y(), -1.0, 0.02);
  EXPECT_GT(blobs[1].radius_m, blobs[0].radius_m);
}

TEST(MovingObstacles, ClusterBlobsSameWhateverTheBinWindow) {
  // The bins in range are counted on a grid over their window, or hashed when the window is too
  // large for a grid (a huge range): the same blobs, in the same order, bit for bit.
  std::vector<Eigen::Vector2d> pts;
  add_square(pts, {1.0, 1.0}, 0.15, 0);
  add_square(pts, {2.0, -1.0}, 0.4, 1);
  add_square(pts, {-1.2, 0.3}, 0.2, 2);
  add_square(pts, {1.1, 1.25}, 0.1, 3);  // touches the first square's bins: one blob
  add_wall(pts, -3.0, 3.0, 2.5);
  pts.emplace_back(-1.5, -1.5);
  const auto near = cluster_blobs(pts, {0.0, 0.0}, enabled_tracking());
  ASSERT_EQ(near.size(), 3u);
  add_square(pts, {900.0, -700.0}, 0.15, 4);  // 16000 x 7000 bins apart
  auto far_params = enabled_tracking();
  far_params.max_range_m = 2000.0;
  const auto all = cluster_blobs(pts, {0.0, 0.0}, far_params);
  ASSERT_EQ(all.size(), 4u);
  for (std::size_t i = 0; i < near.size(); ++i) {
    EXPECT_EQ(all[i].centroid, near[i].centroid);
    EXPECT_EQ(all[i].radius_m, near[i].radius_m);
    EXPECT_EQ(all[i].points, near[i].points);
  }
  EXPECT_NEAR(all[3].centroid.x(), 900.0, 0.02);
}

TEST(MovingObstacles, BoxBesideAPostInALaneStaysItsOwnBlob) {
  // hexagon_dynamic: the 0.15 m box in a 0.8 m lane between r = 0.15 m cylinders (0.325 m gaps).
  // Merged with a cylinder its centroid would jump and its track be lost.
  std::vector<Eigen::Vector2d> pts;
  add_square(pts, {0.55, 0.0}, 0.15, 0);
  for (int i = 0; i < 64; ++i) {
    const double a = 2.0 * M_PI * i / 64.0;
    for (const double cx : {0.0, 1.1}) pts.emplace_back(cx + 0.15 * std::cos(a), 0.15 * std::sin(a));
  }
  const auto blobs = cluster_blobs(pts, {0.0, 0.0}, enabled_tracking());
  ASSERT_EQ(blobs.size(), 3u);
  int boxes = 0;
  for (const auto& b : blobs) boxes += (b.centroid - Eigen::Vector2d(0.55, 0.0)).norm() < 0.02 ? 1 : 0;
  EXPECT_EQ(boxes, 1);
}

TEST(MovingObstacles, ClusterBlobsKeepTheHighestPointAndRejectMismatchedHeights) {
  std::vector<Eigen::Vector2d> pts;
  add_square(pts, {1.0, 1.0}, 0.15, 0);
  std::vector<double> heights(pts.size(), 0.2);
  heights[3] = 0.45;
  const auto blobs = cluster_blobs(pts, {0.0, 0.0}, enabled_tracking(), heights);
  ASSERT_EQ(blobs.size(), 1u);
  EXPECT_DOUBLE_EQ(blobs[0].top_m, 0.45);
  EXPECT_DOUBLE_EQ(cluster_blobs(pts, {0.0, 0.0}, enabled_tracking())[0].top_m, 0.0);
  heights.pop_back();
  EXPECT_THROW(cluster_blobs(pts, {0.0, 0.0}, enabled_tracking(), heights), Error);
}

namespace {

std::uint64_t reference_cell_key(long x, long y) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(x)) << 32) |
         static_cast<std::uint64_t>(static_cast<std::uint32_t>(y));
}

// cluster_blobs before its binning ran four points at a time (AVX2) into kept buffers: the
// bitwise reference of ClusterBlobsBinningMatchesTheScalarCode.
std::vector<Blob> cluster_blobs_scalar_binning(const std::vector<Eigen::Vector2d>& points,
                                               const Eigen::Vector2d& center, const MovingObstacleParams& params,
                                               const std::vector<double>& heights) {
  require(heights.empty() || heights.size() == points.size(), "cluster_blobs heights",
          "empty or one per point (" + std::to_string(points.size()) + "), got " + std::to_string(heights.size()));
  std::vector<Blob> out;
  const double cell = params.cluster_cell_m;
  const double r2max = params.max_range_m * params.max_range_m;
  // The bins of the points in range, in point order.
  std::vector<long> bx, by;
  std::vector<std::size_t> in_range;
  bx.reserve(points.size());
  by.reserve(points.size());
  in_range.reserve(points.size());
  long x_lo = 0, x_hi = -1, y_lo = 0, y_hi = -1;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d& p = points[i];
    if (!p.allFinite() || (p - center).squaredNorm() > r2max) continue;
    const auto x = static_cast<long>(std::floor(p.x() / cell)), y = static_cast<long>(std::floor(p.y() / cell));
    if (in_range.empty()) x_lo = x_hi = x, y_lo = y_hi = y;
    x_lo = std::min(x_lo, x), x_hi = std::max(x_hi, x), y_lo = std::min(y_lo, y), y_hi = std::max(y_hi, y);
    bx.push_back(x);
    by.push_back(y);
    in_range.push_back(i);
  }
  if (in_range.empty()) return out;
  // Cells in a fixed order, (x, y) ascending, each a [begin, end) range of `order` (point indices,
  // ascending within a cell). The bins span a small window (max_range_m around the robot): a
  // counting sort over it; a hash of the bins when the window is too large for that.
  std::vector<std::size_t> order(in_range.size());
  std::vector<std::pair<std::size_t, std::size_t>> cells;
  std::vector<std::pair<long, long>> cell_xy;
  const auto span_x = static_cast<unsigned long>(x_hi - x_lo), span_y = static_cast<unsigned long>(y_hi - y_lo);
  const std::size_t grid_limit = std::max<std::size_t>(1 << 16, 8 * in_range.size());
  const bool dense = span_x < grid_limit && span_y < grid_limit && (span_x + 1) * (span_y + 1) <= grid_limit;
  const auto H = static_cast<std::size_t>(span_y + 1);
  std::vector<std::int32_t> grid;  // dense: cell index per bin, -1 when empty
  std::unordered_map<std::uint64_t, std::size_t> cell_of;
  if (dense) {
    const std::size_t W = static_cast<std::size_t>(span_x + 1);
    std::vector<std::uint32_t> start(W * H + 1, 0);
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
  } else {
    std::vector<std::tuple<long, long, std::size_t>> binned(in_range.size());
    for (std::size_t k = 0; k < in_range.size(); ++k) binned[k] = {bx[k], by[k], in_range[k]};
    std::sort(binned.begin(), binned.end());
    for (std::size_t i = 0; i < binned.size();) {
      std::size_t j = i;
      while (j < binned.size() && std::get<0>(binned[j]) == std::get<0>(binned[i]) &&
             std::get<1>(binned[j]) == std::get<1>(binned[i]))
        ++j;
      cell_of.emplace(reference_cell_key(std::get<0>(binned[i]), std::get<1>(binned[i])), cells.size());
      cells.emplace_back(i, j);
      cell_xy.emplace_back(std::get<0>(binned[i]), std::get<1>(binned[i]));
      i = j;
    }
    for (std::size_t k = 0; k < binned.size(); ++k) order[k] = std::get<2>(binned[k]);
  }
  // The cell at bin (x, y), or -1.
  const auto find_cell = [&](long x, long y) -> std::int64_t {
    if (dense) {
      if (x < x_lo || x > x_hi || y < y_lo || y > y_hi) return -1;
      return grid[static_cast<std::size_t>(x - x_lo) * H + static_cast<std::size_t>(y - y_lo)];
    }
    const auto it = cell_of.find(reference_cell_key(x, y));
    return it == cell_of.end() ? -1 : static_cast<std::int64_t>(it->second);
  };
  std::vector<char> seen(cells.size(), 0);
  std::vector<std::size_t> stack, members;
  for (std::size_t c0 = 0; c0 < cells.size(); ++c0) {
    if (seen[c0]) continue;
    seen[c0] = 1;
    stack.assign(1, c0);
    members.clear();
    while (!stack.empty()) {
      const std::size_t c = stack.back();
      stack.pop_back();
      members.push_back(c);
      const auto [cx, cy] = cell_xy[c];
      for (long dy = -1; dy <= 1; ++dy) {
        for (long dx = -1; dx <= 1; ++dx) {
          const std::int64_t n = find_cell(cx + dx, cy + dy);
          if (n >= 0 && !seen[static_cast<std::size_t>(n)])
            seen[static_cast<std::size_t>(n)] = 1, stack.push_back(static_cast<std::size_t>(n));
        }
      }
    }
    Blob b;
    for (const std::size_t c : members) {
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
    for (const std::size_t c : members) {
      for (std::size_t k = cells[c].first; k < cells[c].second; ++k)
        r2 = std::max(r2, (points[order[k]] - b.centroid).squaredNorm());
    }
    b.radius_m = std::max(b.radius_m, std::sqrt(r2));
    if (b.points < params.min_points || b.radius_m > params.max_blob_radius_m) continue;
    out.push_back(b);
  }
  return out;
}

}  // namespace

// The AVX2 binning (finite test, range test, quotient, floor) gives the scalar code's bins, so the
// same blobs bit for bit: points on cell borders and on the range circle, non-finite points,
// coordinates beyond int32 bins (the scalar fallback, and the sorted bins), every length mod 4, runs
// of points in one bin.
TEST(MovingObstacles, ClusterBlobsBinningMatchesTheScalarCode) {
  std::uint64_t state = 12345;
  const auto uniform = [&] {  // splitmix64 in [0, 1)
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  };
  MovingObstacleParams params = enabled_tracking();
  params.min_points = 1;
  params.max_blob_radius_m = 1e300;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Vector2d center(4.0 * uniform() - 2.0, 4.0 * uniform() - 2.0);
    std::vector<Eigen::Vector2d> pts;
    std::vector<double> heights;
    const int n = trial % 37 + static_cast<int>(400 * uniform());
    for (int i = 0; i < n; ++i) {
      const double kind = uniform();
      Eigen::Vector2d p(center.x() + 12.0 * uniform() - 6.0, center.y() + 12.0 * uniform() - 6.0);
      if (kind < 0.1) {  // on a cell border
        p = Eigen::Vector2d(std::round(p.x() * 10.0) * 0.1, std::round(p.y() * 10.0) / 10.0);
      } else if (kind < 0.15) {  // on (or next to) the range circle
        const double a = 6.283185307179586 * uniform();
        p = center + params.max_range_m * Eigen::Vector2d(std::cos(a), std::sin(a));
      } else if (kind < 0.18) {
        p = Eigen::Vector2d(uniform() < 0.5 ? nan : inf, p.y());
      } else if (kind < 0.2) {
        p = Eigen::Vector2d(p.x(), uniform() < 0.5 ? -inf : nan);
      } else if (kind < 0.6 && !pts.empty()) {  // runs of points in one bin (or the next)
        p = pts.back() + Eigen::Vector2d(0.02 * uniform() - 0.01, 0.02 * uniform() - 0.01);
      }
      pts.push_back(p);
      heights.push_back(uniform() < 0.05 ? nan : uniform());
    }
    MovingObstacleParams q = params;
    if (trial % 5 == 4) q.max_range_m = 1e12;  // bins beyond int32 (and a window too large for the grid)
    if (trial % 5 == 4)
      for (int i = 0; i < n; i += 7) pts[static_cast<std::size_t>(i)] *= 1e10;
    const auto got = cluster_blobs(pts, center, q, trial % 2 ? heights : std::vector<double>{});
    const auto want = cluster_blobs_scalar_binning(pts, center, q, trial % 2 ? heights : std::vector<double>{});
    ASSERT_EQ(got.size(), want.size()) << "trial " << trial;
    for (std::size_t b = 0; b < got.size(); ++b) {
      EXPECT_EQ(got[b].points, want[b].points);
      EXPECT_EQ(std::memcmp(&got[b].centroid, &want[b].centroid, sizeof(Eigen::Vector2d)), 0) << "trial " << trial;
      EXPECT_EQ(std::memcmp(&got[b].radius_m, &want[b].radius_m, sizeof(double)), 0);
      EXPECT_EQ(std::memcmp(&got[b].top_m, &want[b].top_m, sizeof(double)), 0);
    }
  }
}

}  // namespace bipednav::planning::local
