#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "bipednav/common/angles.hpp"
#include "bipednav/common/point_cloud.hpp"
#include "bipednav/common/se3.hpp"
#include "bipednav/sim/gaussian_noise.hpp"
#include "bipednav/sim/raycaster.hpp"

namespace bipednav::sim {

// Velodyne VLP-16 (thesis 2.1.3): 16 rings evenly spread over [-15, +15] deg, 0.2 deg azimuth
// steps (1800 columns), 10 Hz, up to 100 m.
struct Vlp16Params {
  int rings = 16;
  double min_elevation_rad = deg2rad(-15.0);
  double max_elevation_rad = deg2rad(15.0);
  int columns = 1800;  // per revolution
  double rate_hz = 10.0;
  double min_range_m = 0.3;
  double max_range_m = 100.0;
  double range_noise_stddev_m = 0.02;  // Gaussian, along the beam

  void validate() const;
};

// Scanning LiDAR simulated column by column. Column c of sweep k fires at
// t = (k * columns + c) / (rate_hz * columns), from the sensor pose at that instant (motion
// distortion is real). The head spins clockwise seen from above, as a Velodyne does: column c
// points at azimuth -2 pi c / columns in the sensor frame (0 = +x).
//
// Output of a sweep: points in the sensor frame *at each point's firing time*, column-major
// (firing order, rings bottom to top within a column), time_offsets_s since the sweep start,
// rings (0 = lowest), stamp_s = sweep start, frame_id as given. Beams with no return (nothing
// within [min_range_m, max_range_m]) produce no point, so size() <= rings * columns.
class Vlp16 {
 public:
  // T_world_sensor at simulated time t_s.
  using PoseAt = std::function<SE3(double t_s)>;

  Vlp16(const Vlp16Params& params, std::string frame_id, std::uint64_t seed);

  // Fires every column whose firing time is < t_end_s. Returns the sweep if this completed it.
  std::optional<PointCloud> fire_until(double t_end_s, const RayCaster& caster, const PoseAt& T_world_sensor_at);
  // Hands back a returned sweep: the next sweep is written into its buffers (no allocation).
  void recycle(PointCloud&& sweep) { spare_ = std::move(sweep); }

  double column_time_s(std::uint64_t sweep, int column) const;
  double ring_elevation_rad(int ring) const;
  double column_azimuth_rad(int column) const;
  // Unit beam direction in the sensor frame: float(cos(el) cos(az)), float(cos(el) sin(az)), float(sin(el)).
  Eigen::Vector3f beam(int column, int ring) const {
    const auto c = static_cast<std::size_t>(column);
    const auto r = static_cast<std::size_t>(ring);
    return {static_cast<float>(cos_el_[r] * cos_az_[c]), static_cast<float>(cos_el_[r] * sin_az_[c]), sin_el_[r]};
  }
  const Vlp16Params& params() const { return params_; }
  std::size_t beam_count() const { return static_cast<std::size_t>(params_.columns) * params_.rings; }

 private:
  // Fires columns [first, first + n) (n <= RayPacket::kWidth) at their own times and poses:
  // one packet per ring, one lane per column.
  void fire_columns(int first, int n, const RayCaster& caster, const PoseAt& T_world_sensor_at);

  Vlp16Params params_;
  std::string frame_id_;
  GaussianNoise noise_;
  std::vector<float> ranges_;  // ring-major, RayPacket::kWidth columns per ring
  // The beams' factors: beam (c, r) = float(cos_el_[r] * cos_az_[c]), float(cos_el_[r] *
  // sin_az_[c]), sin_el_[r]. A packet's beams are formed from these small tables (29 kB) rather
  // than read from a 350 kB table of beams that a sweep would stream through cache. The azimuth
  // tables are padded by a packet width (zeros).
  std::vector<double> cos_az_, sin_az_, cos_el_;
  std::vector<float> sin_el_;
  // Scratch: the current packets' beams, sensor frame, ring-major with kWidth columns per ring.
  std::vector<float> packet_beam_x_, packet_beam_y_, packet_beam_z_;
  std::uint64_t sweep_ = 0;
  int next_column_ = 0;
  PointCloud current_;
  PointCloud spare_;  // a recycled sweep's buffers
};

}  // namespace bipednav::sim
