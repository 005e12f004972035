#include "bipednav/perception/deskew.hpp"

#include <cmath>
#include <limits>

namespace bipednav::perception {

bool deskew_sweep(const PointCloud& sweep, const SE3& T_base_sensor, const Twist& v, double to_stamp_s,
                  PointCloud& out) {
  if (!sweep.has_time() || sweep.time_offsets_s.size() != sweep.size() || !v.is_finite() || !std::isfinite(to_stamp_s))
    return false;
  if (v.is_zero()) return false;
  const Eigen::Matrix3d R_bs = T_base_sensor.linear();
  const Eigen::Vector3d t_bs = T_base_sensor.translation();
  const Eigen::Matrix3d R_sb = R_bs.transpose();
  out.clear();
  out.stamp_s = to_stamp_s;
  out.frame_id = sweep.frame_id;
  out.points.resize(sweep.size());
  // Points come column by column, each column at one firing time: the motion is computed once per
  // distinct time offset.
  float last_offset = std::numeric_limits<float>::quiet_NaN();
  Eigen::Matrix3d M = Eigen::Matrix3d::Identity();  // sensor(firing) -> sensor(to_stamp) rotation
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < sweep.size(); ++i) {
    const float offset = sweep.time_offsets_s[i];
    if (!(offset == last_offset)) {
      last_offset = offset;
      const double dt = sweep.stamp_s + static_cast<double>(offset) - to_stamp_s;  // <= 0 for past points
      const double th = v.angular_z * dt, c = std::cos(th), s = std::sin(th);
      // V(th) of the SE(2) exponential, by series near th = 0.
      const double a = std::abs(th) < 1e-6 ? 1.0 - th * th / 6.0 : s / th;
      const double b = std::abs(th) < 1e-6 ? th / 2.0 : (1.0 - c) / th;
      const double vx = v.linear_x * dt, vy = v.linear_y * dt;
      Eigen::Matrix3d Rz = Eigen::Matrix3d::Identity();
      Rz << c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0;
      const Eigen::Vector3d t(a * vx - b * vy, b * vx + a * vy, 0.0);
      // p_sensor(to) = R_sb * (Rz * (R_bs * p + t_bs) + t - t_bs)
      M = R_sb * Rz * R_bs;
      m = R_sb * (Rz * t_bs + t - t_bs);
    }
    out.points[i] = (M * sweep.points[i].cast<double>() + m).cast<float>();
  }
  return true;
}

}  // namespace bipednav::perception
