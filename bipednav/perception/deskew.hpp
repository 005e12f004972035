#pragma once

#include "bipednav/common/point_cloud.hpp"
#include "bipednav/common/se3.hpp"
#include "bipednav/common/twist.hpp"

namespace bipednav::perception {

// Motion compensation of a LiDAR sweep for the maps (LOAM de-skews for itself, eq. 4.8-4.10): each
// point is given in the sensor frame at its own firing time (sweep.stamp_s + time_offsets_s[i]); it
// is moved into the sensor frame at `to_stamp_s` for a base moving with the constant planar body
// twist `v` (linear_x, linear_y, angular_z) in between, the pose change being the twist's
// exponential (se3_exp). Without it a robot turning at 1.8 rad/s places the start of a 0.1 s sweep 0.18 rad
// off, 0.5 m sideways at 2.8 m. `out` gets the points only (no time offsets or rings). Returns
// false and leaves `out` untouched when the sweep has no time offsets or the twist is zero or not
// finite (the sweep is then used as it is).
bool deskew_sweep(const PointCloud& sweep, const SE3& T_base_sensor, const Twist& v, double to_stamp_s,
                  PointCloud& out);

}  // namespace bipednav::perception
