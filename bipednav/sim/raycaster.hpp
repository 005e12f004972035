#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <memory>
#include <span>

#include "bipednav/sim/depth_raster.hpp"
#include "bipednav/sim/shape_tessellation.hpp"
#include "bipednav/sim/world.hpp"

namespace bipednav::sim {

// Up to 16 rays cast together as one Embree packet, in structure-of-arrays layout. Every ray
// has its own origin (e.g. LiDAR columns fired at different times). Rays [0, count) are cast;
// the other lanes are ignored (need not be set).
struct RayPacket {
  static constexpr int kWidth = 16;
  alignas(64) float org_x[kWidth];
  alignas(64) float org_y[kWidth];
  alignas(64) float org_z[kWidth];
  alignas(64) float dir_x[kWidth];  // unit length
  alignas(64) float dir_y[kWidth];
  alignas(64) float dir_z[kWidth];
  int count = 0;
};

struct RayCasterParams {
  int threads = 1;  // Embree worker threads (BVH builds); 1 keeps a simulation on one core
  TessellationParams tessellation;

  void validate() const;
};

// Ray casting against a World on Embree 3. The static geometry is one triangle scene built
// once; each actor is its own scene placed by an instance whose transform set_time() updates
// (only the small scene of actor instances is rebuilt; rays visit it after the static scene). Unbounded horizontal
// planes (the ground) are intersected analytically, outside the BVH. Curved shapes are tessellated with facets that
// straddle the true surface (radial error <= params.tessellation.max_chord_error_m, 0.5 mm by
// default). Casting is const and thread-safe; set_time() is not. Move-only (owns the device).
class RayCaster {
 public:
  explicit RayCaster(const World& world, const RayCasterParams& params = {});
  ~RayCaster();
  RayCaster(RayCaster&&) noexcept;
  RayCaster& operator=(RayCaster&&) noexcept;
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  // Moves the actors to their scripted poses at simulated time t_s (no-op if unchanged).
  void set_time(double t_s);
  double time_s() const;

  // Distance from `origin` along `dir` (normalised here) to the first surface within
  // max_range_m; +infinity when nothing is hit.
  float cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, float max_range_m) const;

  // Casts rays from one origin along unit directions (world frame), 16 at a time
  // (cast_packet); ranges[i] is the hit distance or +infinity. `coherent` hints that
  // neighbouring rays are similar (camera tiles).
  void cast_batch(const Eigen::Vector3f& origin, std::span<const Eigen::Vector3f> unit_dirs, float max_range_m,
                  std::span<float> ranges, bool coherent = false) const {
    cast_batch(origin, Eigen::Matrix3f::Identity(), unit_dirs, max_range_m, ranges, coherent);
  }
  // Same, with directions given in a sensor frame rotated by R_world_sensor.
  void cast_batch(const Eigen::Vector3f& origin, const Eigen::Matrix3f& R_world_sensor,
                  std::span<const Eigen::Vector3f> unit_dirs_sensor, float max_range_m, std::span<float> ranges,
                  bool coherent = false) const;

  // Casts one packet; ranges[i] (i < p.count) is the hit distance or +infinity. `coherent`
  // hints that the rays are similar (neighbouring pixels, neighbouring LiDAR columns).
  void cast_packet(const RayPacket& p, float max_range_m, float* ranges, bool coherent = false) const;

  // The same triangles, planes and actor poses (at time_s()) for rasterising depth images.
  const RasterScene& raster_scene() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bipednav::sim
