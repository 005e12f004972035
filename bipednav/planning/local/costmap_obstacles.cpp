#include "bipednav/planning/local/costmap_obstacles.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>

namespace bipednav::planning::local {

namespace {

double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

// std::sort of s.keyed (block, then position), by a counting sort over the component's block window:
// the positions come in ascending order, so a stable placement by block gives the same order. A
// window of more than 4096 blocks is left to std::sort.
void sort_by_block(ObstacleScratch& s) {
  if (s.keyed.empty()) return;
  long x_lo = s.keyed[0].first.first, x_hi = x_lo, y_lo = s.keyed[0].first.second, y_hi = y_lo;
  bool ascending = true;
  for (std::size_t k = 0; k < s.keyed.size(); ++k) {
    const auto& [b, j] = s.keyed[k];
    x_lo = std::min(x_lo, b.first), x_hi = std::max(x_hi, b.first);
    y_lo = std::min(y_lo, b.second), y_hi = std::max(y_hi, b.second);
    if (k > 0 && j <= s.keyed[k - 1].second) ascending = false;
  }
  const auto w = static_cast<unsigned long>(x_hi - x_lo), h = static_cast<unsigned long>(y_hi - y_lo);
  if (!ascending || w >= 4096 || h >= 4096 || (w + 1) * (h + 1) > 4096) {
    std::sort(s.keyed.begin(), s.keyed.end());
    return;
  }
  const std::size_t H = h + 1, buckets = (w + 1) * H;
  const auto bucket = [&](const std::pair<long, long>& b) {
    return static_cast<std::size_t>(b.first - x_lo) * H + static_cast<std::size_t>(b.second - y_lo);
  };
  s.bucket_start.assign(buckets + 1, 0);
  for (const auto& e : s.keyed) ++s.bucket_start[bucket(e.first) + 1];
  for (std::size_t b = 0; b < buckets; ++b) s.bucket_start[b + 1] += s.bucket_start[b];
  s.sorted.resize(s.keyed.size());
  for (const auto& e : s.keyed) s.sorted[s.bucket_start[bucket(e.first)]++] = e;
  s.keyed.swap(s.sorted);
}

// 8-connected components of the lethal cells into s.cells / s.comp_end: components in the order of their
// first cell in scan order, each component's cells in scan order.
void lethal_components(const mapping::Costmap2D& costmap, ObstacleScratch& s) {
  const auto& g = costmap.geometry();
  const std::uint8_t* data = costmap.data().data();
  const std::size_t n = costmap.data().size();
  s.seen.assign(n, 0);
  s.cells.clear();
  s.comp_end.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const void* next = std::memchr(data + i, mapping::kLethal, n - i);  // the next lethal cell
    if (next == nullptr) break;
    i = static_cast<std::size_t>(static_cast<const std::uint8_t*>(next) - data);
    if (s.seen[i] != 0) continue;
    const std::size_t begin = s.cells.size();
    s.seen[i] = 1;
    s.stack.assign(1, i);
    while (!s.stack.empty()) {
      const std::size_t c = s.stack.back();
      s.stack.pop_back();
      s.cells.push_back(c);
      const mapping::Cell cell = g.cell_of(c);
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = cell.x + dx, ny = cell.y + dy;
          if (!g.in_bounds(nx, ny)) continue;
          const std::size_t m = g.index(nx, ny);
          if (data[m] == mapping::kLethal && s.seen[m] == 0) s.seen[m] = 1, s.stack.push_back(m);
        }
      }
    }
    std::sort(s.cells.begin() + static_cast<long>(begin), s.cells.end());
    s.comp_end.push_back(s.cells.size());
  }
}

}  // namespace

std::vector<Eigen::Vector2d> convex_hull(std::vector<Eigen::Vector2d> pts) {
  std::sort(pts.begin(), pts.end(),
            [](const auto& a, const auto& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  if (pts.size() < 3) return pts;
  std::vector<Eigen::Vector2d> hull(2 * pts.size());
  std::size_t k = 0;
  for (const auto& p : pts) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p) <= 0.0) --k;
    hull[k++] = p;
  }
  for (std::size_t i = pts.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0.0) --k;
    hull[k++] = pts[i];
  }
  hull.resize(k - 1);
  return hull;
}

Obstacle make_obstacle(const std::vector<Eigen::Vector2d>& pts, double half_cell_m, const ObstacleParams& params) {
  Obstacle o;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : pts) mean += p;
  mean /= static_cast<double>(pts.size());
  o.centroid = mean;
  double rmax = 0.0;
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const auto& p : pts) {
    rmax = std::max(rmax, (p - mean).norm());
    cov += (p - mean) * (p - mean).transpose();
  }
  o.radius_m = rmax + half_cell_m;
  if (2.0 * rmax <= params.point_max_extent_m) {
    o.kind = Obstacle::Kind::kPoint;
    o.vertices = {mean};
    return o;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(cov);
  const Eigen::Vector2d major = es.eigenvectors().col(1);
  const Eigen::Vector2d minor = es.eigenvectors().col(0);
  double lo = 1e300, hi = -1e300, wlo = 1e300, whi = -1e300;
  for (const auto& p : pts) {
    const double s = (p - mean).dot(major), w = (p - mean).dot(minor);
    lo = std::min(lo, s), hi = std::max(hi, s), wlo = std::min(wlo, w), whi = std::max(whi, w);
  }
  if (whi - wlo <= params.line_max_width_m) {
    o.kind = Obstacle::Kind::kLine;
    o.vertices = {mean + lo * major, mean + hi * major};
    return o;
  }
  // The hull of the cells' corners only needs the first and last cell of each row (equal y): the corners of
  // the cells between lie on the segments joining theirs (same y), so they are never hull vertices. Cells
  // come in scan order (rows, then x) from extract_obstacles; other orders are sorted first.
  const auto row_less = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.y() < b.y() || (a.y() == b.y() && a.x() < b.x());
  };
  std::vector<Eigen::Vector2d> sorted;
  const std::vector<Eigen::Vector2d>* rows = &pts;
  if (!std::is_sorted(pts.begin(), pts.end(), row_less)) {
    sorted = pts;
    std::sort(sorted.begin(), sorted.end(), row_less);
    rows = &sorted;
  }
  std::vector<Eigen::Vector2d> corners;
  const auto add_corners = [&](const Eigen::Vector2d& p) {
    for (const double sx : {-half_cell_m, half_cell_m})
      for (const double sy : {-half_cell_m, half_cell_m}) corners.emplace_back(p.x() + sx, p.y() + sy);
  };
  for (std::size_t i = 0; i < rows->size();) {
    std::size_t j = i + 1;
    while (j < rows->size() && (*rows)[j].y() == (*rows)[i].y()) ++j;
    add_corners((*rows)[i]);
    if (j - 1 > i) add_corners((*rows)[j - 1]);
    i = j;
  }
  o.kind = Obstacle::Kind::kPolygon;
  o.vertices = convex_hull(std::move(corners));
  return o;
}

std::vector<Obstacle> extract_obstacles(const mapping::Costmap2D& costmap, const ObstacleParams& params,
                                        ObstacleScratch* scratch) {
  std::vector<Obstacle> out;
  if (costmap.width() <= 0 || costmap.height() <= 0) return out;
  const auto& g = costmap.geometry();
  const double half = 0.5 * g.resolution_m;
  ObstacleScratch own;
  ObstacleScratch& s = scratch != nullptr ? *scratch : own;
  lethal_components(costmap, s);
  std::size_t begin = 0;
  for (const std::size_t end : s.comp_end) {
    // Cut large components into blocks so that hulls stay local (a wall's L or U stays concave). Blocks in
    // order of (column, row) of the block, each block's cells in scan order.
    s.keyed.clear();
    s.centres.clear();
    for (std::size_t j = begin; j < end; ++j) {
      const Eigen::Vector2d c = g.cell_center(g.cell_of(s.cells[j]));
      s.centres.push_back(c);
      s.keyed.push_back({{static_cast<long>(std::floor(c.x() / params.cluster_block_m)),
                          static_cast<long>(std::floor(c.y() / params.cluster_block_m))},
                         j});
    }
    sort_by_block(s);
    for (std::size_t k = 0; k < s.keyed.size();) {
      s.pts.clear();
      std::size_t l = k;
      for (; l < s.keyed.size() && s.keyed[l].first == s.keyed[k].first; ++l)
        s.pts.push_back(s.centres[s.keyed[l].second - begin]);
      if (static_cast<int>(out.size()) >= params.max_obstacles) return out;
      out.push_back(make_obstacle(s.pts, half, params));
      k = l;
    }
    begin = end;
  }
  return out;
}

std::vector<int> nearest_obstacles(const std::vector<Obstacle>& obstacles, const Eigen::Vector2d& p, int k,
                                   double max_dist_m, std::vector<std::pair<double, int>>* candidates) {
  std::vector<std::pair<double, int>> own;
  std::vector<std::pair<double, int>>& cand = candidates != nullptr ? *candidates : own;
  cand.clear();
  for (std::size_t i = 0; i < obstacles.size(); ++i) {
    // Cheap bounding-circle rejection before the exact distance.
    if ((obstacles[i].centroid - p).norm() - obstacles[i].radius_m > max_dist_m) continue;
    const double d = obstacle_distance(obstacles[i], p.x(), p.y());
    if (d <= max_dist_m) cand.emplace_back(d, static_cast<int>(i));
  }
  const std::size_t n = std::min<std::size_t>(cand.size(), static_cast<std::size_t>(std::max(k, 0)));
  std::partial_sort(cand.begin(), cand.begin() + static_cast<long>(n), cand.end());
  std::vector<int> idx(n);
  for (std::size_t i = 0; i < n; ++i) idx[i] = cand[i].second;
  return idx;
}

}  // namespace bipednav::planning::local
