#include "bipednav/sim/depth_camera.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "bipednav/common/error.hpp"
#include "bipednav/common/simd4.hpp"

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
  require(renderer == "raster" || renderer == "raycast", "renderer", "'raster' or 'raycast'");
}

DepthCamera::DepthCamera(const DepthCameraParams& params, std::string frame_id, std::uint64_t seed)
    : params_(params), frame_id_(std::move(frame_id)), noise_(seed) {
  params_.validate();
  constexpr int W = RayPacket::kWidth;
  const int w = params_.width, h = params_.height;
  const std::size_t lanes = static_cast<std::size_t>((w + 3) / 4) * static_cast<std::size_t>((h + 3) / 4) * W;
  for (auto* v : {&ray_x_, &ray_y_, &ray_z_}) v->reserve(lanes);
  pixel_.reserve(lanes);
  float min_x = 1.0f;
  for (int tv = 0; tv < h; tv += 4)
    for (int tu = 0; tu < w; tu += 4) {
      const std::size_t first = pixel_.size();
      for (int v = tv; v < std::min(tv + 4, h); ++v)
        for (int u = tu; u < std::min(tu + 4, w); ++u) {
          const Eigen::Vector3f r = pixel_ray(u, v);
          ray_x_.push_back(r.x());
          ray_y_.push_back(r.y());
          ray_z_.push_back(r.z());
          pixel_.push_back(v * w + u);
          min_x = std::min(min_x, r.x());
        }
      tile_count_.push_back(static_cast<int>(pixel_.size() - first));
      while (pixel_.size() - first < W) {
        for (auto* vec : {&ray_x_, &ray_y_, &ray_z_}) vec->push_back((*vec)[first]);
        pixel_.push_back(pixel_[first]);
      }
    }
  const double fx = 0.5 * w / std::tan(0.5 * params_.hfov_rad);
  const double fy = 0.5 * h / std::tan(0.5 * params_.vfov_rad);
  for (int u = 0; u < w; ++u) slope_u_.push_back(static_cast<float>(-(u + 0.5 - 0.5 * w) / fx));
  for (int v = 0; v < h; ++v) slope_v_.push_back(static_cast<float>(-(v + 0.5 - 0.5 * h) / fy));
  for (int u = 0; u < w / 4 * 4; ++u)
    slope_xyz_.insert(slope_xyz_.end(), {1.0f, slope_u_[static_cast<std::size_t>(u)], 0.0f});
  // A ray can reach depth max_range_m at range max_range_m / cos(angle to the axis).
  max_cast_m_ = static_cast<float>(params_.max_range_m / min_x) * 1.01f;
  if (params_.renderer == "raster")
    rasterizer_ = DepthRasterizer(slope_u_, slope_v_, static_cast<float>(params_.max_range_m));
  depth_.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  noise_row_.resize(static_cast<std::size_t>(w));
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
  PointCloud c = std::move(spare_);  // a recycled cloud's buffers, or none
  spare_ = PointCloud{};
  render_into(c, next_capture_s(), T_world_camera, caster);
  ++count_;
  return c;
}

void DepthCamera::skip_capture() {
  noise_.skip(static_cast<std::uint64_t>(params_.width) * static_cast<std::uint64_t>(params_.height));
  ++count_;
}

PointCloud DepthCamera::capture_at(double stamp_s, const SE3& T_world_camera, const RayCaster& caster) {
  PointCloud c;
  render_into(c, stamp_s, T_world_camera, caster);
  return c;
}

void DepthCamera::render_into(PointCloud& cloud, double stamp_s, const SE3& T_world_camera, const RayCaster& caster) {
  // The rasteriser's rows are read out one by one below (into depth_, a row at a time).
  const bool raster = params_.renderer == "raster";
  if (raster)
    rasterizer_.render(caster.raster_scene(), T_world_camera);
  else
    cast_depth(T_world_camera, caster);

  // Noise and points row by row (noise drawn in pixel order).
  static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float));  // points are packed x y z
  cloud.clear();                                                // every point is written below
  cloud.frame_id = frame_id_;
  cloud.stamp_s = stamp_s;
  const auto w = static_cast<std::size_t>(params_.width);
  cloud.points.resize(depth_.size());
  Eigen::Vector3f* out = cloud.points.data();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const auto z_min = static_cast<float>(params_.min_range_m), z_max = static_cast<float>(params_.max_range_m);
  const auto k = static_cast<float>(params_.noise_coeff_per_m);
  const float* su = slope_u_.data();
  float* noise = noise_row_.data();
  using namespace simd4;
  // The lanes of a block's 12 floats x0 y0 z0 x1 | y1 z1 x2 y2 | z2 x3 y3 z3 that are z.
  const I4 z_lanes[3] = {I4{0, 0, -1, 0}, I4{0, -1, 0, 0}, I4{-1, 0, 0, -1}};
  for (std::size_t v = 0; v < slope_v_.size(); ++v) {
    noise_.fill(noise_row_);
    const float sv = slope_v_[v];
    const float* z_row = depth_.data() + (raster ? 0 : v * w);
    if (raster) rasterizer_.depth_row(static_cast<int>(v), depth_.data());
    Eigen::Vector3f* out_row = out + v * w;
    // slope_xyz_ with sv in its zeros (bitwise: exactly (1, su, sv) per pixel).
    const I4 sv_bits[3] = {(I4)splat(sv) & z_lanes[0], (I4)splat(sv) & z_lanes[1], (I4)splat(sv) & z_lanes[2]};
    const float* slopes = slope_xyz_.data();
    std::size_t u = 0;
    for (; u + 4 <= w; u += 4, slopes += 12) {
      const F4 z = load(z_row + u);
      const F4 z_noisy = z + splat(k) * z * z * load(noise + u);
      const I4 ok = (z >= z_min) & (z <= z_max) & (z_noisy > 0.0f);
      const F4 x = select(ok, z_noisy, splat(nan));
      // Point i is x_i * (1, su_i, sv): x_i itself (x * 1 is exact, NaN included), x_i * su_i and
      // x_i * sv, the same products as x, x * su, x * sv lane by lane.
      float* o = out_row[u].data();
      store(o, shuffle<0, 0, 0, 1>(x, x) * (F4)((I4)load(slopes) | sv_bits[0]));
      store(o + 4, shuffle<1, 1, 2, 2>(x, x) * (F4)((I4)load(slopes + 4) | sv_bits[1]));
      store(o + 8, shuffle<2, 3, 3, 3>(x, x) * (F4)((I4)load(slopes + 8) | sv_bits[2]));
    }
    for (; u < w; ++u) {
      const float z = z_row[u];
      const float z_noisy = z + k * z * z * noise[u];
      const float x = z >= z_min && z <= z_max && z_noisy > 0.0f ? z_noisy : nan;
      out_row[u] = Eigen::Vector3f(x, x * su[u], x * sv);
    }
  }
}

// One Embree ray per pixel, tile by tile; keeps the depth (distance along the optical axis).
void DepthCamera::cast_depth(const SE3& T_world_camera, const RayCaster& caster) {
  constexpr int W = RayPacket::kWidth;
  const Eigen::Matrix3f R = T_world_camera.linear().cast<float>();
  const Eigen::Vector3f o = T_world_camera.translation().cast<float>();
  RayPacket packet;
  for (int i = 0; i < W; ++i) {
    packet.org_x[i] = o.x();
    packet.org_y[i] = o.y();
    packet.org_z[i] = o.z();
  }
  alignas(64) float ranges[W];
  float* depth = depth_.data();
  for (std::size_t t = 0; t < tile_count_.size(); ++t) {
    const std::size_t base = t * W;
    const float* rx = &ray_x_[base];
    const float* ry = &ray_y_[base];
    const float* rz = &ray_z_[base];
    for (int i = 0; i < W; ++i) {
      packet.dir_x[i] = R(0, 0) * rx[i] + R(0, 1) * ry[i] + R(0, 2) * rz[i];
      packet.dir_y[i] = R(1, 0) * rx[i] + R(1, 1) * ry[i] + R(1, 2) * rz[i];
      packet.dir_z[i] = R(2, 0) * rx[i] + R(2, 1) * ry[i] + R(2, 2) * rz[i];
    }
    packet.count = tile_count_[t];
    caster.cast_packet(packet, max_cast_m_, ranges, true);
    const int* pix = &pixel_[base];
    for (int i = 0; i < packet.count; ++i) depth[pix[i]] = ranges[i] * rx[i];  // +inf without a hit
  }
}

}  // namespace bipednav::sim
