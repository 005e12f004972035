#include "bench/synthetic_scene.hpp"

#include <cmath>
#include <limits>

#include "bipednav/common/error.hpp"
#include "bipednav/common/rng.hpp"

namespace bipednav::bench {
namespace {

constexpr double kNoHit = std::numeric_limits<double>::infinity();

// Slab test: distance along the unit ray to the box, or kNoHit.
double hit_box(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const SyntheticBox& b) {
  double t0 = 0.0, t1 = kNoHit;
  for (int a = 0; a < 3; ++a) {
    if (std::fabs(d[a]) < 1e-12) {
      if (o[a] < b.min_m[a] || o[a] > b.max_m[a]) return kNoHit;
      continue;
    }
    double ta = (b.min_m[a] - o[a]) / d[a], tb = (b.max_m[a] - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return kNoHit;
  }
  return t0 > 1e-9 ? t0 : kNoHit;
}

std::vector<SyntheticBox> scene_boxes(const SyntheticSceneParams& p) {
  std::vector<SyntheticBox> boxes = p.boxes;
  const double hx = p.room_x_m / 2, hy = p.room_y_m / 2, h = p.wall_height_m, w = 0.1;
  boxes.push_back({{-hx - w, -hy, 0}, {-hx, hy, h}});
  boxes.push_back({{hx, -hy, 0}, {hx + w, hy, h}});
  boxes.push_back({{-hx, -hy - w, 0}, {hx, -hy, h}});
  boxes.push_back({{-hx, hy, 0}, {hx, hy + w, h}});
  return boxes;
}

double cast(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const std::vector<SyntheticBox>& boxes) {
  double t = d.z() < -1e-12 ? -o.z() / d.z() : kNoHit;  // the floor z = 0
  for (const auto& b : boxes) t = std::min(t, hit_box(o, d, b));
  return t;
}

DepthCloud depth_cloud(const SensorMount& m, const SyntheticSceneParams& p, const std::vector<SyntheticBox>& boxes,
                       Rng& rng) {
  DepthCloud out{m.name, {}};
  out.cloud.frame_id = m.name;
  const SE3 T = m.T_base_sensor();
  const double fx = (p.depth_width / 2.0) / std::tan(p.depth_hfov_rad / 2);
  const double fy = (p.depth_height / 2.0) / std::tan(p.depth_vfov_rad / 2);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  out.cloud.points.reserve(static_cast<std::size_t>(p.depth_width * p.depth_height));
  for (int r = 0; r < p.depth_height; ++r)
    for (int c = 0; c < p.depth_width; ++c) {
      // Pixel ray in the sensor frame (x forward, y left, z up); depth is measured along x.
      const Eigen::Vector3d ray(1.0, -(c + 0.5 - p.depth_width / 2.0) / fx, -(r + 0.5 - p.depth_height / 2.0) / fy);
      const double t = cast(T.translation(), T.linear() * ray.normalized(), boxes) / ray.norm();
      if (!(t >= p.depth_min_m && t <= p.depth_max_m)) {
        out.cloud.points.emplace_back(nan, nan, nan);
        continue;
      }
      const double depth = t + rng.normal(0.0, p.depth_noise_per_m2 * t * t);
      out.cloud.points.push_back((ray * depth).cast<float>());
    }
  return out;
}

PointCloud lidar_sweep(const SensorMount& m, const SyntheticSceneParams& p, const std::vector<SyntheticBox>& boxes,
                       Rng& rng) {
  PointCloud c;
  c.frame_id = m.name;
  const SE3 T = m.T_base_sensor();
  const int steps = static_cast<int>(std::lround(2 * M_PI / p.lidar_azimuth_step_rad));
  for (int s = 0; s < steps; ++s) {
    const double az = s * p.lidar_azimuth_step_rad;
    for (int ring = 0; ring < p.lidar_rings; ++ring) {
      const double el = (-15.0 + 30.0 * ring / std::max(1, p.lidar_rings - 1)) * M_PI / 180.0;
      const Eigen::Vector3d d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
      const double t = cast(T.translation(), T.linear() * d, boxes);
      if (!(t <= p.lidar_max_m)) continue;
      c.points.push_back((d * (t + rng.normal(0.0, p.lidar_noise_m))).cast<float>());
      c.rings.push_back(static_cast<std::uint16_t>(ring));
      c.time_offsets_s.push_back(static_cast<float>(0.1 * s / steps));
    }
  }
  return c;
}

}  // namespace

RobotProfile synthetic_digit_profile() {
  RobotProfile r;
  r.name = "digit_synthetic";
  r.kind = "walker";
  r.footprint_radius_m = 0.35;
  r.height_m = 1.6;
  const double pitch = M_PI / 4;
  r.sensors = {{"lidar", "vlp16", 0.0, 0.0, 1.47, 0.0, 0.0, 0.0},
               {"depth_front", "d430", 0.1, 0.0, 1.0, 0.0, pitch, 0.0},
               {"depth_back", "d430", -0.1, 0.0, 1.0, 0.0, pitch, M_PI}};
  return r;
}

SensorFrame synthetic_digit_frame(const RobotProfile& robot, const SyntheticSceneParams& params) {
  require(params.depth_width > 0 && params.depth_height > 0, "depth_width", "> 0 pixels");
  require(params.lidar_rings > 0 && params.lidar_azimuth_step_rad > 0, "lidar_rings", "> 0");
  Rng rng(params.seed);
  const auto boxes = scene_boxes(params);
  SensorFrame f;
  for (const SensorMount& m : robot.sensors) {
    if (m.type == "d430") f.depth.push_back(depth_cloud(m, params, boxes, rng));
    if (m.type == "vlp16") f.lidar = lidar_sweep(m, params, boxes, rng);
  }
  return f;
}

}  // namespace bipednav::bench
