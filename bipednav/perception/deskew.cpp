#include "bipednav/perception/deskew.hpp"

#include <cmath>
#include <limits>

namespace bipednav::perception {

bool deskew_sweep(const PointCloud& sweep, const SE3& T_base_sensor, const Twist& v, double to_stamp_s,
                  PointCloud& out) {
  if (!sweep.has_time() || sweep.time_offsets_s.size() != sweep.size() || !v.is_finite() || !std::isfinite(to_stamp_s))
    return false;
  if (v.is_zero()) return false;
  Eigen::Matrix<double, 6, 1> twist;  // (rho, phi) of the base, constant over the sweep
  twist << v.linear_x, v.linear_y, 0.0, 0.0, 0.0, v.angular_z;
  const SE3 T_sensor_base = T_base_sensor.inverse();
  out.clear();
  out.stamp_s = to_stamp_s;
  out.frame_id = sweep.frame_id;
  out.points.resize(sweep.size());
  // Points come column by column, each column at one firing time: the motion is computed once per
  // distinct time offset.
  float last_offset = std::numeric_limits<float>::quiet_NaN();
  SE3 T = SE3::Identity();  // sensor at the firing time -> sensor at to_stamp_s
  for (std::size_t i = 0; i < sweep.size(); ++i) {
    const float offset = sweep.time_offsets_s[i];
    if (!(offset == last_offset)) {
      last_offset = offset;
      const double dt = sweep.stamp_s + static_cast<double>(offset) - to_stamp_s;  // <= 0 for past points
      T = T_sensor_base * se3_exp(twist * dt) * T_base_sensor;
    }
    out.points[i] = (T * sweep.points[i].cast<double>()).cast<float>();
  }
  return true;
}

}  // namespace bipednav::perception
