#include "bipednav/tracking/clustering.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <utility>

namespace bipednav::tracking {

namespace {

struct BinnedPoint {
  std::int64_t x, y;
  std::size_t index;
  bool operator<(const BinnedPoint& o) const { return x != o.x ? x < o.x : (y != o.y ? y < o.y : index < o.index); }
};

std::uint64_t cluster_cell_key(std::int64_t x, std::int64_t y) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(x)) << 32) |
         static_cast<std::uint64_t>(static_cast<std::uint32_t>(y));
}

}  // namespace

std::vector<std::vector<std::size_t>> euclidean_clusters(std::span<const Eigen::Vector3d> points, double cell_m,
                                                         int min_points) {
  std::vector<BinnedPoint> binned;
  binned.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double fx = std::floor(points[i].x() / cell_m), fy = std::floor(points[i].y() / cell_m);
    if (!points[i].allFinite() || !(std::abs(fx) < 1e9 && std::abs(fy) < 1e9)) continue;
    binned.push_back({static_cast<std::int64_t>(fx), static_cast<std::int64_t>(fy), i});
  }
  std::sort(binned.begin(), binned.end());
  // Occupied cells as runs [begin, end) of `binned`, found by their key.
  std::vector<std::pair<std::size_t, std::size_t>> runs;
  std::unordered_map<std::uint64_t, std::size_t> run_of;
  for (std::size_t b = 0; b < binned.size();) {
    std::size_t e = b;
    while (e < binned.size() && binned[e].x == binned[b].x && binned[e].y == binned[b].y) ++e;
    run_of.emplace(cluster_cell_key(binned[b].x, binned[b].y), runs.size());
    runs.emplace_back(b, e);
    b = e;
  }
  std::vector<std::vector<std::size_t>> clusters;
  std::vector<char> seen(runs.size(), 0);
  std::vector<std::size_t> stack;
  for (std::size_t r0 = 0; r0 < runs.size(); ++r0) {
    if (seen[r0]) continue;
    seen[r0] = 1;
    stack.assign(1, r0);
    std::vector<std::size_t> members;
    while (!stack.empty()) {
      const std::size_t r = stack.back();
      stack.pop_back();
      for (std::size_t k = runs[r].first; k < runs[r].second; ++k) members.push_back(binned[k].index);
      const BinnedPoint& c = binned[runs[r].first];
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        for (std::int64_t dx = -1; dx <= 1; ++dx) {
          const auto it = run_of.find(cluster_cell_key(c.x + dx, c.y + dy));
          if (it == run_of.end() || seen[it->second]) continue;
          seen[it->second] = 1;
          stack.push_back(it->second);
        }
      }
    }
    if (static_cast<int>(members.size()) < min_points) continue;
    std::sort(members.begin(), members.end());
    clusters.push_back(std::move(members));
  }
  std::sort(clusters.begin(), clusters.end(), [](const auto& a, const auto& b) { return a.front() < b.front(); });
  return clusters;
}

}  // namespace bipednav::tracking
