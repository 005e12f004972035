#pragma once

#include <Eigen/Geometry>

#include "bipednav/common/pose2.hpp"

namespace bipednav {

using SE3 = Eigen::Isometry3d;

// Rotation from roll, pitch, yaw (ZYX convention, as in REP-103).
inline Eigen::Matrix3d rpy_to_matrix(double roll, double pitch, double yaw) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

// Roll, pitch, yaw of a rotation matrix (ZYX convention).
inline Eigen::Vector3d matrix_to_rpy(const Eigen::Matrix3d& R) {
  const double pitch = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  return {std::atan2(R(2, 1), R(2, 2)), pitch, std::atan2(R(1, 0), R(0, 0))};
}

inline SE3 make_se3(double x, double y, double z, double roll, double pitch, double yaw) {
  SE3 T = SE3::Identity();
  T.linear() = rpy_to_matrix(roll, pitch, yaw);
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

inline SE3 se3_from_pose2(const Pose2& p, double z = 0.0) { return make_se3(p.x, p.y, z, 0.0, 0.0, p.theta); }

// Projects a 3D pose onto the ground plane (x, y, yaw).
inline Pose2 pose2_from_se3(const SE3& T) {
  const Eigen::Matrix3d& R = T.linear();
  return {T.translation().x(), T.translation().y(), std::atan2(R(1, 0), R(0, 0))};
}

// Exponential map of a twist (rho, phi) in R^6 to SE(3).
inline SE3 se3_exp(const Eigen::Matrix<double, 6, 1>& xi) {
  const Eigen::Vector3d rho = xi.head<3>(), phi = xi.tail<3>();
  const double angle = phi.norm();
  SE3 T = SE3::Identity();
  if (angle < 1e-10) {
    T.linear() = Eigen::Matrix3d::Identity();
    T.translation() = rho;
    return T;
  }
  const Eigen::Vector3d axis = phi / angle;
  Eigen::Matrix3d K;
  K << 0, -axis.z(), axis.y(), axis.z(), 0, -axis.x(), -axis.y(), axis.x(), 0;
  const Eigen::Matrix3d V =
      Eigen::Matrix3d::Identity() + (1 - std::cos(angle)) / angle * K + (angle - std::sin(angle)) / angle * K * K;
  T.linear() = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
  T.translation() = V * rho;
  return T;
}

// Interpolates between two poses: s = 0 gives a, s = 1 gives b (slerp on rotation).
inline SE3 se3_interpolate(const SE3& a, const SE3& b, double s) {
  const Eigen::Quaterniond qa(a.linear()), qb(b.linear());
  SE3 T = SE3::Identity();
  T.linear() = qa.slerp(s, qb).toRotationMatrix();
  T.translation() = (1.0 - s) * a.translation() + s * b.translation();
  return T;
}

}  // namespace bipednav
