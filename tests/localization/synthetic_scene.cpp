#include "synthetic_scene.hpp"

#include <cmath>
#include <numbers>

namespace bipednav::test {

namespace {

// Slab test in the box frame: the entry distance from outside, the exit distance from inside.
std::optional<double> cast_box(const SceneBox& b, const Eigen::Vector3d& o_w, const Eigen::Vector3d& d_w) {
  const SE3 T_box_world = b.T_world_box.inverse();
  const Eigen::Vector3d o = T_box_world * o_w;
  const Eigen::Vector3d d = T_box_world.linear() * d_w;
  double t_near = -1e30, t_far = 1e30;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) < 1e-12) {
      if (std::abs(o[i]) > b.half_size[i]) return std::nullopt;
      continue;
    }
    double t1 = (-b.half_size[i] - o[i]) / d[i], t2 = (b.half_size[i] - o[i]) / d[i];
    if (t1 > t2) std::swap(t1, t2);
    t_near = std::max(t_near, t1);
    t_far = std::min(t_far, t2);
  }
  if (t_near > t_far) return std::nullopt;
  const double t = b.inside ? t_far : t_near;
  if (t <= 1e-6) return std::nullopt;
  return t;
}

}  // namespace

std::optional<double> SyntheticScene::cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                                           double max_range) const {
  std::optional<double> best;
  for (const auto& b : boxes) {
    const auto t = cast_box(b, origin, dir);
    if (t && *t <= max_range && (!best || *t < *best)) best = t;
  }
  return best;
}

SyntheticScene room_scene() {
  SyntheticScene s;
  s.boxes.push_back({make_se3(0, 0, 1.5, 0, 0, 0), {6, 4, 1.5}, true});
  s.boxes.push_back({make_se3(2, 1.5, 1.5, 0, 0, 0), {0.2, 0.2, 1.5}, false});
  s.boxes.push_back({make_se3(-3, -2, 0.5, 0, 0, 0.5), {0.5, 0.3, 0.5}, false});
  s.boxes.push_back({make_se3(4, -2.5, 1.5, 0, 0, 0.3), {0.15, 0.15, 1.5}, false});
  s.boxes.push_back({make_se3(-2, 2.5, 0.8, 0, 0, -0.4), {0.6, 0.4, 0.8}, false});
  s.boxes.push_back({make_se3(5.6, 2.0, 1.5, 0, 0, 0), {0.4, 0.6, 1.5}, false});
  s.boxes.push_back({make_se3(-5.5, 0.5, 1.0, 0, 0, 0.7), {0.3, 0.3, 1.0}, false});
  return s;
}

SyntheticScene corridor_scene() {
  SyntheticScene s;
  s.boxes.push_back({make_se3(0, 0, 1.5, 0, 0, 0), {500, 1, 1.5}, true});
  return s;
}

PointCloud synthetic_sweep(const SyntheticScene& scene, const std::function<SE3(double)>& T_world_lidar_at, double t0,
                           const SweepSpec& spec, Rng& rng, std::vector<Eigen::Vector3d>* world_points) {
  PointCloud cloud;
  cloud.frame_id = "lidar";
  cloud.stamp_s = t0;
  if (world_points) world_points->clear();
  const double min_el = -15.0 * std::numbers::pi / 180.0, max_el = 15.0 * std::numbers::pi / 180.0;
  for (int c = 0; c < spec.columns; ++c) {
    const double dt = spec.period_s * c / spec.columns;
    const SE3 T = T_world_lidar_at(t0 + dt);
    const double az = -2.0 * std::numbers::pi * c / spec.columns;
    for (int r = 0; r < spec.rings; ++r) {
      const double el = min_el + (max_el - min_el) * r / (spec.rings - 1);
      const Eigen::Vector3d beam(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
      const auto range = scene.cast(T.translation(), T.linear() * beam, spec.max_range_m);
      if (!range) continue;
      const double measured = *range + rng.normal(0.0, spec.noise_m);
      cloud.points.push_back((measured * beam).cast<float>());
      cloud.time_offsets_s.push_back(static_cast<float>(dt));
      cloud.rings.push_back(static_cast<std::uint16_t>(r));
      if (world_points) world_points->push_back(T * (*range * beam));
    }
  }
  return cloud;
}

}  // namespace bipednav::test
