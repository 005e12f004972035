#include "bipednav/sim/vlp16.hpp"

#include <cmath>
#include <numbers>

#include "bipednav/common/error.hpp"
#include "bipednav/common/simd4.hpp"

namespace bipednav::sim {

void Vlp16Params::validate() const {
  require(rings >= 1 && rings <= 512, "rings", "in [1, 512]");
  require(std::isfinite(min_elevation_rad) && std::isfinite(max_elevation_rad) &&
              min_elevation_rad <= max_elevation_rad && min_elevation_rad > -std::numbers::pi / 2 &&
              max_elevation_rad < std::numbers::pi / 2,
          "min_elevation_rad/max_elevation_rad", "min <= max within (-pi/2, pi/2)");
  require(rings > 1 || min_elevation_rad == max_elevation_rad, "rings",
          "> 1 when the elevation range is not a single angle");
  require(columns >= 1 && columns <= 100000, "columns", "in [1, 100000]");
  require(rate_hz > 0 && std::isfinite(rate_hz), "rate_hz", "> 0");
  require(min_range_m >= 0 && std::isfinite(min_range_m), "min_range_m", ">= 0");
  require(max_range_m > min_range_m && std::isfinite(max_range_m), "max_range_m", "> min_range_m and finite");
  require(range_noise_stddev_m >= 0 && std::isfinite(range_noise_stddev_m), "range_noise_stddev_m", ">= 0");
}

Vlp16::Vlp16(const Vlp16Params& params, std::string frame_id, std::uint64_t seed)
    : params_(params), frame_id_(std::move(frame_id)), noise_(seed) {
  params_.validate();
  ranges_.resize(static_cast<std::size_t>(params_.rings) * RayPacket::kWidth);
  const std::size_t padded = static_cast<std::size_t>(params_.columns) + RayPacket::kWidth;
  cos_az_.assign(padded, 0.0);
  sin_az_.assign(padded, 0.0);
  for (int c = 0; c < params_.columns; ++c) {
    const double az = column_azimuth_rad(c);
    cos_az_[static_cast<std::size_t>(c)] = std::cos(az);
    sin_az_[static_cast<std::size_t>(c)] = std::sin(az);
  }
  for (int r = 0; r < params_.rings; ++r) {
    const double el = ring_elevation_rad(r);
    cos_el_.push_back(std::cos(el));
    sin_el_.push_back(static_cast<float>(std::sin(el)));
  }
  for (auto* v : {&packet_beam_x_, &packet_beam_y_, &packet_beam_z_}) v->assign(ranges_.size(), 0.0f);
}

double Vlp16::ring_elevation_rad(int ring) const {
  if (params_.rings == 1) return params_.min_elevation_rad;
  return params_.min_elevation_rad +
         (params_.max_elevation_rad - params_.min_elevation_rad) * ring / static_cast<double>(params_.rings - 1);
}

double Vlp16::column_azimuth_rad(int column) const {
  return normalize_angle(-2.0 * std::numbers::pi * column / params_.columns);
}

double Vlp16::column_time_s(std::uint64_t sweep, int column) const {
  const double ticks = static_cast<double>(sweep * static_cast<std::uint64_t>(params_.columns) + column);
  return ticks / (params_.rate_hz * params_.columns);
}

void Vlp16::fire_columns(int first, int n, const RayCaster& caster, const PoseAt& T_world_sensor_at) {
  constexpr int W = RayPacket::kWidth;
  const int rings = params_.rings;
  // Every column has its own firing time and sensor pose; a packet holds one ring of up to 16
  // neighbouring columns (0.2 deg apart: coherent rays, each from its own origin).
  alignas(16) float R[3][3][W] = {};  // R[i][j][k]: entry (i, j) of column k's rotation
  RayPacket packet;
  float dt[W];
  for (int k = 0; k < n; ++k) {
    const double t = column_time_s(sweep_, first + k);
    const SE3 T = T_world_sensor_at(t);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) R[i][j][k] = static_cast<float>(T.linear()(i, j));
    const Eigen::Vector3f o = T.translation().cast<float>();
    packet.org_x[k] = o.x();
    packet.org_y[k] = o.y();
    packet.org_z[k] = o.z();
    dt[k] = static_cast<float>(t - current_.stamp_s);
  }
  packet.count = n;
  const auto max_range = static_cast<float>(params_.max_range_m);
  using namespace simd4;
  const double* cos_az = &cos_az_[static_cast<std::size_t>(first)];
  const double* sin_az = &sin_az_[static_cast<std::size_t>(first)];
  for (int r = 0; r < rings; ++r) {
    // The beams of all 16 lanes (columns past n are ignored by the caster), sensor frame.
    const std::size_t b = static_cast<std::size_t>(r) * W;
    float* beam_x = &packet_beam_x_[b];
    float* beam_y = &packet_beam_y_[b];
    float* beam_z = &packet_beam_z_[b];
    const double ce = cos_el_[static_cast<std::size_t>(r)];
    for (int k = 0; k < W; ++k) {
      beam_x[k] = static_cast<float>(ce * cos_az[k]);
      beam_y[k] = static_cast<float>(ce * sin_az[k]);
      beam_z[k] = sin_el_[static_cast<std::size_t>(r)];
    }
    // dir = R_k * beam, 4 columns at once.
    for (int k = 0; k < W; k += 4) {
      const F4 bx = load(beam_x + k), by = load(beam_y + k), bz = load(beam_z + k);
      float* dir[3] = {packet.dir_x, packet.dir_y, packet.dir_z};
      for (int i = 0; i < 3; ++i)
        store(dir[i] + k, load(&R[i][0][k]) * bx + load(&R[i][1][k]) * by + load(&R[i][2][k]) * bz);
    }
    caster.cast_packet(packet, max_range, &ranges_[b], true);
  }
  // Output in firing order: column by column, rings bottom to top.
  // Written in place (room for every beam, trimmed after): the points appended in order.
  const auto sigma = static_cast<float>(params_.range_noise_stddev_m);
  const double range_lo = params_.min_range_m, range_hi = params_.max_range_m;
  const std::size_t base = current_.points.size(), room = static_cast<std::size_t>(n) * static_cast<std::size_t>(rings);
  current_.points.resize(base + room);
  current_.time_offsets_s.resize(base + room);
  current_.rings.resize(base + room);
  Eigen::Vector3f* points = current_.points.data() + base;
  float* times = current_.time_offsets_s.data() + base;
  std::uint16_t* ring_of = current_.rings.data() + base;
  std::size_t m = 0;
  for (int k = 0; k < n; ++k)
    for (int r = 0; r < rings; ++r) {
      const std::size_t i = static_cast<std::size_t>(r) * W + static_cast<std::size_t>(k);
      const float range = ranges_[i];
      if (!(range >= range_lo && range <= range_hi)) continue;
      const float noisy = range + sigma * noise_();
      points[m] = Eigen::Vector3f(packet_beam_x_[i] * noisy, packet_beam_y_[i] * noisy, packet_beam_z_[i] * noisy);
      times[m] = dt[k];
      ring_of[m++] = static_cast<std::uint16_t>(r);
    }
  current_.points.resize(base + m);
  current_.time_offsets_s.resize(base + m);
  current_.rings.resize(base + m);
}

std::optional<PointCloud> Vlp16::fire_until(double t_end_s, const RayCaster& caster, const PoseAt& T_world_sensor_at) {
  std::optional<PointCloud> done;
  for (;;) {
    const double t = column_time_s(sweep_, next_column_);
    if (t >= t_end_s) break;
    if (next_column_ == 0) {
      current_ = std::move(spare_);  // a recycled sweep's buffers, or none
      spare_ = PointCloud{};
      current_.clear();
      current_.frame_id = frame_id_;
      current_.stamp_s = t;
      current_.reserve(beam_count());
      current_.time_offsets_s.reserve(beam_count());
      current_.rings.reserve(beam_count());
    }
    // The columns of this sweep due before t_end_s, up to one packet width.
    int n = 1;
    while (n < RayPacket::kWidth && next_column_ + n < params_.columns &&
           column_time_s(sweep_, next_column_ + n) < t_end_s)
      ++n;
    fire_columns(next_column_, n, caster, T_world_sensor_at);
    next_column_ += n;
    if (next_column_ == params_.columns) {
      next_column_ = 0;
      ++sweep_;
      done = std::move(current_);
      current_ = PointCloud{};
    }
  }
  return done;
}

}  // namespace bipednav::sim
