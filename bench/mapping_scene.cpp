#include "bench/mapping_scene.hpp"

#include <algorithm>
#include <cmath>

namespace bipednav::bench {

namespace {

constexpr double kRoomHalfX = 5.0, kRoomHalfY = 4.0, kCylinderRadius = 0.25;

std::vector<Eigen::Vector2d> cylinders() {
  std::vector<Eigen::Vector2d> c;
  for (int i = 0; i < 6; ++i) c.emplace_back(2.5 * std::cos(i * M_PI / 3), 2.5 * std::sin(i * M_PI / 3));
  c.emplace_back(1.2, 0.3);
  c.emplace_back(-1.0, -1.1);
  c.emplace_back(-0.4, 1.5);
  return c;
}

// Distance along a horizontal ray to the first wall or cylinder.
double cast_2d(const Eigen::Vector2d& o, const Eigen::Vector2d& d, const std::vector<Eigen::Vector2d>& cyl) {
  double best = 1e9;
  for (int k = 0; k < 2; ++k) {
    const double half = k == 0 ? kRoomHalfX : kRoomHalfY;
    if (d[k] > 1e-12) best = std::min(best, (half - o[k]) / d[k]);
    if (d[k] < -1e-12) best = std::min(best, (-half - o[k]) / d[k]);
  }
  for (const auto& c : cyl) {
    const Eigen::Vector2d oc = o - c;
    const double b = oc.dot(d), cc = oc.squaredNorm() - kCylinderRadius * kCylinderRadius;
    const double disc = b * b - cc;
    if (disc < 0.0) continue;
    const double t = -b - std::sqrt(disc);
    if (t > 0.0) best = std::min(best, t);
  }
  return best;
}

// Appends the obstacle-height return of a ray (unit horizontal direction, elevation) if any.
void add_return(mapping::Observation& obs, const Eigen::Vector2d& d, double elevation, double max_range,
                const std::vector<Eigen::Vector2d>& cyl) {
  const Eigen::Vector2d o = obs.origin_map.head<2>();
  const double r = cast_2d(o, d, cyl);
  const double z = obs.origin_map.z() + r * std::tan(elevation);
  if (z < 0.05 || z > 2.0 || r / std::cos(elevation) > max_range) return;  // ground, over the top, or too far
  const Eigen::Vector2d p = o + r * d;
  obs.points_map.emplace_back(float(p.x()), float(p.y()), float(z));
}

}  // namespace

SyntheticObservations synthetic_digit_observations(const Pose2& T_map_base) {
  const auto cyl = cylinders();
  SyntheticObservations f;
  mapping::Observation lidar;
  lidar.origin_map = {T_map_base.x, T_map_base.y, 1.2};
  lidar.max_range_m = 100.0;
  for (int a = 0; a < 1800; ++a) {
    const double az = T_map_base.theta + 2.0 * M_PI * a / 1800.0;
    for (int ring = 0; ring < 16; ++ring)
      add_return(lidar, {std::cos(az), std::sin(az)}, (-15.0 + 2.0 * ring) * M_PI / 180.0, 100.0, cyl);
  }
  f.lidar_points = lidar.points_map.size();
  f.observations.push_back(std::move(lidar));
  for (double yaw : {0.0, M_PI}) {
    mapping::Observation cam;
    cam.origin_map = {T_map_base.x + 0.1 * std::cos(T_map_base.theta + yaw),
                      T_map_base.y + 0.1 * std::sin(T_map_base.theta + yaw), 1.0};
    cam.max_range_m = 4.0;
    for (int v = 0; v < 120; ++v) {
      const double el = (-29.0 + 58.0 * (v + 0.5) / 120.0) * M_PI / 180.0;
      for (int u = 0; u < 212; ++u) {
        const double az = T_map_base.theta + yaw + (-43.5 + 87.0 * (u + 0.5) / 212.0) * M_PI / 180.0;
        add_return(cam, {std::cos(az), std::sin(az)}, el, 4.0, cyl);
      }
    }
    f.depth_points += cam.points_map.size();
    f.observations.push_back(std::move(cam));
  }
  return f;
}

std::vector<Eigen::Vector3f> synthetic_terrain_cloud(std::size_t n, double size_m, Rng& rng) {
  std::vector<Eigen::Vector3f> pts;
  pts.reserve(n);
  // Raster order with jitter, like the pixels of a depth image projected onto the ground.
  const auto side = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(n))));
  const double step = size_m / static_cast<double>(side);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = std::clamp((static_cast<double>(i % side) + rng.uniform()) * step, 0.0, size_m);
    const double y = std::clamp((static_cast<double>(i / side) + rng.uniform()) * step, 0.0, size_m);
    double z = 0.15 * std::floor(3.0 * x / size_m);                     // three steps
    if (std::fmod(x, 1.0) < 0.3 && std::fmod(y, 1.0) < 0.3) z += 0.25;  // boxes
    pts.emplace_back(float(x), float(y), float(z + rng.normal(0.0, 0.01)));
  }
  return pts;
}

}  // namespace bipednav::bench
