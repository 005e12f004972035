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
  for (int tv = 0; tv < h; tv += 4)
    for (int tu = 0; tu < w; tu += 4)
      for (int v = tv; v < std::min(tv + 4, h); ++v)
        for (int u = tu; u < std::min(tu + 4, w); ++u) order_.push_back(v * w + u);
  rays_.reserve(order_.size());
  for (int p : order_) rays_.push_back(pixel_ray(p % w, p / w));
  world_dirs_.resize(rays_.size());
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
  const Eigen::Matrix3f R = T_world_camera.linear().cast<float>();
  for (std::size_t i = 0; i < rays_.size(); ++i) world_dirs_[i] = R * rays_[i];
  // A ray can reach depth max_range_m at range max_range_m / cos(angle to the axis).
  const float max_cast = static_cast<float>(params_.max_range_m / rays_.front().x()) * 1.01f;
  caster.cast_batch(T_world_camera.translation().cast<float>(), world_dirs_, max_cast, ranges_, true);

  PointCloud cloud;
  cloud.frame_id = frame_id_;
  cloud.stamp_s = stamp_s;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  cloud.points.assign(rays_.size(), Eigen::Vector3f(nan, nan, nan));
  const auto z_min = static_cast<float>(params_.min_range_m), z_max = static_cast<float>(params_.max_range_m);
  const auto k = static_cast<float>(params_.noise_coeff_per_m);
  for (std::size_t i = 0; i < rays_.size(); ++i) {
    const float z = ranges_[i] * rays_[i].x();  // depth; +inf (no hit) fails the test below
    if (!(z >= z_min && z <= z_max)) continue;
    const float z_noisy = z + k * z * z * noise_();
    if (!(z_noisy > 0.0f)) continue;
    cloud.points[order_[i]] = rays_[i] * (ranges_[i] * z_noisy / z);
  }
  return cloud;
}

}  // namespace bipednav::sim
