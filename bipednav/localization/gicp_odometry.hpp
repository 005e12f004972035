#pragma once

#include <optional>

#include "bipednav/common/point_cloud.hpp"
#include "bipednav/common/se3.hpp"
#include "bipednav/localization/gicp.hpp"

namespace bipednav::localization {

// Scan-to-scan Generalized-ICP odometry: each sweep is aligned to the previous one, starting from
// the previous motion (constant velocity), and the motions are chained. No features, no map, no
// de-skew: the baseline LOAM is compared with (`bipednav odometry --method gicp`).
struct GicpOdometryParams {
  GicpParams gicp{};
  std::size_t min_points = 100;  // fewer points in a sweep: its motion is the constant-velocity guess
  void validate() const;
};

struct GicpOdometryOutput {
  SE3 T_world_lidar = SE3::Identity();
  SE3 T_prev_lidar = SE3::Identity();  // the motion since the previous sweep
  bool healthy = true;                 // false: the motion is the guess (first sweep excepted)
  GicpResult gicp;                     // of the alignment (default on the first sweep)
  double time_ms = 0.0;                // covariances and alignment
};

class GicpOdometry {
 public:
  explicit GicpOdometry(GicpOdometryParams p = {}, const SE3& T_world_lidar_initial = SE3::Identity());
  // One sweep in the LiDAR frame (down-sampled by the caller: GICP's cost grows with the points).
  GicpOdometryOutput process(const PointCloud& sweep);

 private:
  GicpOdometryParams p_;
  std::optional<GicpCloud> previous_;
  SE3 T_world_lidar_;
  SE3 last_motion_ = SE3::Identity();
  std::size_t sweeps_ = 0;
};

}  // namespace bipednav::localization
