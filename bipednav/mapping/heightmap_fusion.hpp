#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

#include "bipednav/common/point_cloud.hpp"
#include "bipednav/common/pose2.hpp"
#include "bipednav/mapping/heightmap.hpp"

namespace bipednav::mapping {

// Per-cell Kalman height filter of section IV of the humanoid reference (eq. 2-3).
struct HeightmapFusionParams {
  double variance_per_m2 = 1e-4;              // sigma_z^2 = variance_per_m2 * (distance to sensor)^2
  double min_observation_variance_m2 = 1e-6;  // floor of sigma_z^2 (points right at the sensor)
  double min_cell_variance_m2 = 1e-6;         // the belief never gets stiffer than this
  double max_cell_variance_m2 = 1.0;          // cap of the variance raised by gate failures
  double gate_sigma = 3.0;                    // Mahalanobis gate on (z - h) / sqrt(sigma_c^2 + sigma_z^2)
  double variance_growth_factor = 4.0;        // sigma_c^2 *= this when an observation fails the gate
  double max_range_m = 10.0;                  // points farther from the sensor are ignored

  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v("variance_per_m2", variance_per_m2);
    v("min_observation_variance_m2", min_observation_variance_m2);
    v("min_cell_variance_m2", min_cell_variance_m2);
    v("max_cell_variance_m2", max_cell_variance_m2);
    v("gate_sigma", gate_sigma);
    v("variance_growth_factor", variance_growth_factor);
    v("max_range_m", max_range_m);
  }
};

// Result of fusing one observation into one cell.
enum class FuseResult { kInitialised, kFused, kRejected };

// One Kalman update (eq. 2-3) of a cell's belief N(h, var) with an observation z of variance
// var_z. An unknown cell (non-finite h) takes the observation. An observation failing the gate
// leaves h unchanged and multiplies var by variance_growth_factor, so that a real change (a moved
// object) is accepted after a few frames while a single outlier is not.
FuseResult fuse_height(float& h, float& var, float z, float var_z, const HeightmapFusionParams& p);

struct HeightmapUpdateStats {
  std::size_t points_used = 0;     // finite, in the map and in range
  std::size_t cells_fused = 0;     // initialised or fused
  std::size_t cells_rejected = 0;  // failed the gate
};

// Fuses point clouds (world frame) into a Heightmap: points are binned into cells, the highest
// point per cell is the observation z_c, its variance grows with the squared sensor distance.
class HeightmapFusion {
 public:
  explicit HeightmapFusion(const GridGeometry& geometry, const HeightmapFusionParams& params = {});

  HeightmapUpdateStats update(const std::vector<Eigen::Vector3f>& points_world, const Eigen::Vector3d& sensor_world);
  HeightmapUpdateStats update(const PointCloud& cloud_world, const Eigen::Vector3d& sensor_world) {
    return update(cloud_world.points, sensor_world);
  }

  const Heightmap& map() const { return map_; }
  Heightmap& map() { return map_; }
  const HeightmapFusionParams& params() const { return params_; }

 private:
  HeightmapFusionParams params_;
  Heightmap map_;
  // Scratch per cell: highest z this update (-inf between updates) and its squared distance to the
  // sensor, interleaved (separate arrays 4 KiB apart stall store forwarding: 4x slower).
  struct Bin {
    float z;
    float d2;
  };
  std::vector<Bin> bins_;
};

// Heights under a rotated rectangle (centre pose, length along its heading, width across):
// min/max over observed cells whose centre lies inside (NaN when none).
struct FootprintHeights {
  float min_m = 0.0f;
  float max_m = 0.0f;
  int known_cells = 0;
  int cells = 0;
};
FootprintHeights footprint_heights(const Heightmap& map, const Pose2& center, double length_m, double width_m);

}  // namespace bipednav::mapping
