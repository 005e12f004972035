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

// The test of one point, with the parameters prepared once (float, squared ranges).
class PassThroughTest {
 public:
  PassThroughTest(const PassThroughParams& params, const Eigen::Vector3f& origin = Eigen::Vector3f::Zero(),
                  const Plane& plane = ground_plane_z0());
  bool keep(const Eigen::Vector3f& p) const {
    const float r2 = (p - origin_).squaredNorm();
    const float h = signed_distance(plane_, p);
    return p.allFinite() && r2 >= r2_min_ && r2 <= r2_max_ && h >= h_min_ && h <= h_max_;
  }

 private:
  Eigen::Vector3f origin_;
  Eigen::Vector4f plane_;
  float r2_min_, r2_max_, h_min_, h_max_;
};

// Keeps the finite points whose distance to `origin` is in [min_range_m, max_range_m] and whose
// signed height above `plane` (unit normal, as from normalize_plane) is in
// [min_height_m, max_height_m]. NaN and infinite points are always dropped. Optional fields follow
// their points; frame and stamp are copied.
PointCloud pass_through(const PointCloud& in, const PassThroughParams& params,
                        const Eigen::Vector3f& origin = Eigen::Vector3f::Zero(),
                        const Plane& plane = ground_plane_z0());

}  // namespace bipednav::perception
