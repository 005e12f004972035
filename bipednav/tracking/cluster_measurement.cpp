#include "bipednav/tracking/cluster_measurement.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bipednav::tracking {

Detection measure_cluster(std::span<const Eigen::Vector3d> points, const std::vector<std::size_t>& members,
                          const Eigen::Vector2d& viewpoint, const TrackerParams& params, bool heights_known) {
  Detection d;
  if (members.empty()) return d;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  double bottom = std::numeric_limits<double>::infinity();
  for (const std::size_t i : members) {
    mean += points[i].head<2>();
    d.top_m = std::max(d.top_m, points[i].z()), bottom = std::min(bottom, points[i].z());
  }
  if (heights_known) d.height_span_m = d.top_m - bottom;
  mean /= static_cast<double>(members.size());
  d.points = static_cast<int>(members.size());
  // Line of sight u from the viewpoint through the centroid, w across it (a viewpoint inside the
  // cluster: any direction).
  Eigen::Vector2d u = mean - viewpoint;
  u = u.norm() > 1e-9 ? Eigen::Vector2d(u.normalized()) : Eigen::Vector2d::UnitX();
  const Eigen::Vector2d w(-u.y(), u.x());
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const std::size_t i : members) {
    const double l = (points[i].head<2>() - viewpoint).dot(w);
    lo = std::min(lo, l), hi = std::max(hi, l);
  }
  const double half_width = 0.5 * (hi - lo), middle = 0.5 * (hi + lo);
  std::vector<double> near_ranges;
  const double band = 0.125 * (hi - lo) + params.point_noise_m;
  for (const std::size_t i : members) {
    const Eigen::Vector2d v = points[i].head<2>() - viewpoint;
    if (std::abs(v.dot(w) - middle) <= band) near_ranges.push_back(v.dot(u));
  }
  if (near_ranges.empty()) {  // nothing in the middle (two groups side by side): every point's range
    for (const std::size_t i : members) near_ranges.push_back((points[i].head<2>() - viewpoint).dot(u));
  }
  const auto k = static_cast<std::size_t>(params.near_surface_quantile * static_cast<double>(near_ranges.size() - 1));
  const auto near = near_ranges.begin() + static_cast<std::ptrdiff_t>(k);
  std::nth_element(near_ranges.begin(), near, near_ranges.end());
  d.surface = viewpoint + u * *near + w * middle;
  d.position = d.surface + u * half_width;
  double r2 = 0.0;
  for (const std::size_t i : members) r2 = std::max(r2, (points[i].head<2>() - d.position).squaredNorm());
  d.radius_m = std::max(half_width, std::sqrt(r2));
  const double s2 = params.point_noise_m * params.point_noise_m;
  const double along = params.shape_noise_ratio * half_width, across = params.lateral_noise_ratio * half_width;
  Eigen::Matrix2d B;
  B.col(0) = u, B.col(1) = w;
  d.covariance = B * Eigen::Vector2d(s2 + along * along, s2 + across * across).asDiagonal() * B.transpose();
  return d;
}

}  // namespace bipednav::tracking
