#include "bipednav/sim/depth_camera.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include "bipednav/common/error.hpp"

namespace bipednav::sim {

void DepthCameraParams::validate() const {
  require(width >= 1 && width <= 8192, "width", "in [1, 8192] pixels");
  require(height >= 1 && height <= 8192, "height", "in [1, 8192] pixels");
  require(hfov_rad > 0 && hfov_rad < std::numbers::pi, "hfov_rad", "in (0, pi)");
  require(vfov_rad > 0 && vfov_rad < std::numbers::pi, "vfov_rad", "in (0, pi)");
  require(min_range_m >= 0 && std::isfinite(min_range_m), "min_range_m", ">= 0");
  require(max_range_m > min_range_m && std::isfinite(max_range_m), "max_range_m", "> min_range_m and finite");
  require(noise_coeff_per_m >= 0 && std::isfinite(noise_coeff_per_m), "noise_coeff_per_m", ">= 0");
  require(rate_hz > 0 && std::isfinite(rate_hz), "rate_hz", "> 0");
}

DepthCamera::DepthCamera(const DepthCameraParams& params, std::string frame_id, std::uint64_t seed)
    : params_(params), frame_id_(std::move(frame_id)), noise_(seed) {
  params_.validate();
  const int w = params_.width, h = params_.height;
  ray_of_pixel_.resize(static_cast<std::size_t>(w) * h);
  for (int tv = 0; tv < h; tv += 4)
    for (int tu = 0; tu < w; tu += 4)
      for (int v = tv; v < std::min(tv + 4, h); ++v)
        for (int u = tu; u < std::min(tu + 4, w); ++u) {
          ray_of_pixel_[v * w + u] = static_cast<int>(rays_.size());
          rays_.push_back(pixel_ray(u, v));
        }
  ranges_.resize(rays_.size());
}

Eigen::Vector3f DepthCamera::pixel_ray(int u, int v) const {
  // Image plane at unit depth: pixel centres span the field of view symmetrically.
  const double fx = 0.5 * params_.width / std::tan(0.5 * params_.hfov_rad);
  const double fy = 0.5 * params_.height / std::tan(0.5 * params_.vfov_rad);
  const double x_img = (u + 0.5 - 0.5 * params_.width) / fx;   // right
  const double y_img = (v + 0.5 - 0.5 * params_.height) / fy;  // down
  return Eigen::Vector3d(1.0, -x_img, -y_img).normalized().cast<float>();
}

PointCloud DepthCamera::capture(const SE3& T_world_camera, const RayCaster& caster) {
  PointCloud c = capture_at(next_capture_s(), T_world_camera, caster);
  ++count_;
  return c;
}

PointCloud DepthCamera::capture_at(double stamp_s, const SE3& T_world_camera, const RayCaster& caster) {
  // A ray can reach depth max_range_m at range max_range_m / cos(angle to the axis).
  const float max_cast = static_cast<float>(params_.max_range_m / rays_.front().x()) * 1.01f;
  caster.cast_batch(T_world_camera.translation().cast<float>(), T_world_camera.linear().cast<float>(), rays_, max_cast,
                    ranges_, true);

  PointCloud cloud;
  cloud.frame_id = frame_id_;
  cloud.stamp_s = stamp_s;
  cloud.points.resize(rays_.size());
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const auto z_min = static_cast<float>(params_.min_range_m), z_max = static_cast<float>(params_.max_range_m);
  const auto k = static_cast<float>(params_.noise_coeff_per_m);
  for (std::size_t p = 0; p < cloud.points.size(); ++p) {
    const int i = ray_of_pixel_[p];
    const float z = ranges_[i] * rays_[i].x();  // depth; +inf (no hit) fails the test below
    const float z_noisy = z + k * z * z * noise_();
    cloud.points[p] = z >= z_min && z <= z_max && z_noisy > 0.0f
                          ? Eigen::Vector3f(rays_[i] * (ranges_[i] * z_noisy / z))
                          : Eigen::Vector3f(nan, nan, nan);
  }
  return cloud;
}

}  // namespace bipednav::sim
