#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "bipednav/common/angles.hpp"
#include "bipednav/common/point_cloud.hpp"
#include "bipednav/common/se3.hpp"
#include "bipednav/sim/depth_raster.hpp"
#include "bipednav/sim/gaussian_noise.hpp"
#include "bipednav/sim/raycaster.hpp"

namespace bipednav::sim {

// Intel RealSense D430 depth camera (thesis 2.1.2): 85 x 58 deg, 0.2-10 m.
struct DepthCameraParams {
  int width = 424;
  int height = 240;
  double hfov_rad = deg2rad(85.0);
  double vfov_rad = deg2rad(58.0);
  double min_range_m = 0.2;  // on depth (distance along the optical axis)
  double max_range_m = 10.0;
  double noise_coeff_per_m = 0.003;  // depth noise sigma = noise_coeff_per_m * z^2
  double rate_hz = 15.0;
  // How depth is computed: "raster" (z-buffer of the world's triangles, as Gazebo renders a
  // depth camera) or "raycast" (one Embree ray per pixel, the reference). Both give the same
  // depth to float rounding except on silhouette edges (tests/sim/depth_raster_test.cpp).
  std::string renderer = "raster";

  void validate() const;
};

// Pinhole depth camera. A capture is one instant (global shutter) from one pose. The cloud is
// organised: width * height points, row-major from the top-left pixel, in the camera body
// frame of REP-103 (x forward along the optical axis, y left, z up); pixels without a valid
// return (nothing hit, or depth outside [min_range_m, max_range_m]) are NaN. Captures happen
// at t = k / rate_hz; stamp_s is that time, no per-point times.
class DepthCamera {
 public:
  DepthCamera(const DepthCameraParams& params, std::string frame_id, std::uint64_t seed);

  // Time of the next capture.
  double next_capture_s() const { return static_cast<double>(count_) / params_.rate_hz; }
  double capture_after_next_s() const { return static_cast<double>(count_ + 1) / params_.rate_hz; }
  // Captures the image due at next_capture_s() from T_world_camera and schedules the next one.
  PointCloud capture(const SE3& T_world_camera, const RayCaster& caster);
  // Passes over the image due at next_capture_s() without rendering it: the schedule and the noise
  // stream advance as capture() would advance them, so later captures are the same as if it had
  // been taken.
  void skip_capture();
  // Captures at an arbitrary time without touching the schedule.
  PointCloud capture_at(double stamp_s, const SE3& T_world_camera, const RayCaster& caster);
  // Hands back a returned image's cloud: the next capture() is written into its buffers.
  void recycle(PointCloud&& cloud) { spare_ = std::move(cloud); }

  // Unit ray of pixel (u, v) in the camera body frame.
  Eigen::Vector3f pixel_ray(int u, int v) const;
  const DepthCameraParams& params() const { return params_; }

 private:
  void cast_depth(const SE3& T_world_camera, const RayCaster& caster);
  // The image at stamp_s into `cloud` (its old contents replaced, its buffers reused).
  void render_into(PointCloud& cloud, double stamp_s, const SE3& T_world_camera, const RayCaster& caster);

  DepthCameraParams params_;
  std::string frame_id_;
  GaussianNoise noise_;
  std::uint64_t count_ = 0;
  // Rays are cast in 4 x 4 pixel tiles, one coherent RayPacket per tile. Per lane, tile-major
  // with RayPacket::kWidth lanes per tile (unused lanes of edge tiles repeat lane 0):
  std::vector<float> ray_x_, ray_y_, ray_z_;  // unit ray in the camera frame
  std::vector<int> pixel_;                    // row-major pixel index
  std::vector<int> tile_count_;               // used lanes per tile
  // A pixel's point is depth * (1, slope_u_[u], slope_v_[v]).
  std::vector<float> slope_u_, slope_v_;
  // Per block of 4 pixels of a row, (1, slope_u_[u], 0) for its 4 pixels as 12 floats: a row's
  // points are the depths times these with slope_v_ in the zeros.
  std::vector<float> slope_xyz_;
  float max_cast_m_ = 0.0f;  // range at which the outermost ray reaches max_range_m in depth
  DepthRasterizer rasterizer_;
  std::vector<float> depth_;      // scratch: depth per pixel (row-major; raster: one row), +inf without a hit
  std::vector<float> noise_row_;  // scratch: one row of noise samples
  PointCloud spare_;              // a recycled cloud's buffers, for the next capture()
};

}  // namespace bipednav::sim
