#pragma once

#include <Eigen/Core>
#include <limits>

#include "bipednav/common/point_cloud.hpp"
#include "bipednav/perception/plane.hpp"

namespace bipednav::perception {

// Pass-through / range filter (section 4.2.2). Heights are signed distances to a reference plane
// (the estimated ground, or z = 0 of the cloud's frame), so "drop points below the ground" is
// min_height_m = -margin, and "ignore what is above the robot" is max_height_m = robot height.
struct PassThroughParams {
  double min_range_m = 0.0;                                        // from the sensor origin
  double max_range_m = std::numeric_limits<double>::infinity();    // 2.9 m for the depth cameras
  double min_height_m = -std::numeric_limits<double>::infinity();  // above the reference plane
  double max_height_m = std::numeric_limits<double>::infinity();

  void validate() const;
};

// Keeps the finite points whose distance to `origin` is in [min_range_m, max_range_m] and whose
// signed height above `plane` (unit normal, as from normalize_plane) is in
// [min_height_m, max_height_m]. NaN and infinite points are always dropped. Optional fields follow
// their points; frame and stamp are copied.
PointCloud pass_through(const PointCloud& in, const PassThroughParams& params,
                        const Eigen::Vector3f& origin = Eigen::Vector3f::Zero(),
                        const Plane& plane = ground_plane_z0());

// Indices of the kept points (same test), for callers that carry extra per-point data.
std::vector<std::size_t> pass_through_indices(const std::vector<Eigen::Vector3f>& points,
                                              const PassThroughParams& params, const Eigen::Vector3f& origin,
                                              const Plane& plane);

}  // namespace bipednav::perception
