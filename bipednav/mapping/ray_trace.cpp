#include "bipednav/mapping/ray_trace.hpp"

#include <cmath>

namespace bipednav::mapping {

std::vector<Cell> line_cells(Cell a, Cell b, bool include_end) {
  std::vector<Cell> out;
  out.reserve(static_cast<std::size_t>(std::max(std::abs(b.x - a.x), std::abs(b.y - a.y))) + 1);
  for_each_line_cell(a, b, include_end, [&](int x, int y) { out.push_back({x, y}); });
  return out;
}

bool clip_segment(Eigen::Vector2d& a, Eigen::Vector2d& b, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  const Eigen::Vector2d d = b - a;
  double t0 = 0.0, t1 = 1.0;
  for (int k = 0; k < 2; ++k) {
    const double p[2] = {-d[k], d[k]};
    const double q[2] = {a[k] - lo[k], hi[k] - a[k]};
    for (int s = 0; s < 2; ++s) {
      if (p[s] == 0.0) {
        if (q[s] < 0.0) return false;
        continue;
      }
      const double t = q[s] / p[s];
      if (p[s] < 0.0) {
        if (t > t1) return false;
        t0 = std::max(t0, t);
      } else {
        if (t < t0) return false;
        t1 = std::min(t1, t);
      }
    }
  }
  // An end inside the box stays bit-identical (a0 + 1 * (b - a0) may round away from b, and the
  // caller compares the end to tell a clipped ray from one ending at its return).
  const Eigen::Vector2d a0 = a;
  if (t0 > 0.0) a = a0 + t0 * d;
  if (t1 < 1.0) b = a0 + t1 * d;
  return true;
}

std::optional<ClippedRay> clip_ray(const GridGeometry& g, const Eigen::Vector2d& origin, const Eigen::Vector2d& point,
                                   double max_length_m) {
  return RayClipper(g, origin, max_length_m).clip(point);
}

RayClipper::RayClipper(const GridGeometry& g, const Eigen::Vector2d& origin, double max_length_m)
    : g_(g), origin_(origin), max_length_m_(max_length_m), max_length_sq_(max_length_m * max_length_m * (1.0 - 1e-9)) {
  // Shrink the box by a hair so a clipped end never floors onto the cell past the last one.
  const double eps = 1e-6 * g.resolution_m;
  lo_ = {g.origin_x_m, g.origin_y_m};
  hi_ = {g.origin_x_m + g.size_x_m() - eps, g.origin_y_m + g.size_y_m() - eps};
  if (origin.allFinite()) start_ = g.world_to_cell(origin.x(), origin.y());
  origin_inside_ = start_ && inside(origin);
}

std::optional<ClippedRay> RayClipper::clip(const Eigen::Vector2d& point) const {
  if (!start_ || !point.allFinite()) return std::nullopt;
  // On the grid and shorter than the limit (with a margin for the square root's rounding):
  // the clipping below would leave the ray as it is.
  if (const auto end = unclipped_end(point)) return ClippedRay{*start_, *end, false};
  Eigen::Vector2d a = origin_, b = point;
  bool clipped = false;
  const double len = (b - a).norm();
  if (len > max_length_m_) {
    b = a + (b - a) * (max_length_m_ / len);
    clipped = true;
  }
  const Eigen::Vector2d b_before = b;
  if (!clip_segment(a, b, lo_, hi_)) return std::nullopt;
  if (b != b_before) clipped = true;
  const auto end = g_.world_to_cell(b.x(), b.y());
  if (!end) return std::nullopt;
  return ClippedRay{*start_, *end, clipped};
}

}  // namespace bipednav::mapping
