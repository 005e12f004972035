#include "bipednav/localization/corrected_odometry.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>

#include "bipednav/common/error.hpp"

namespace bipednav::localization {

void CorrectedOdometryParams::validate() const {
  gicp.validate();
  require(ground_band_m >= 0.0, "ground_band_m", ">= 0");
  require(min_points >= static_cast<std::size_t>(gicp.covariance_neighbours), "min_points",
          ">= gicp.covariance_neighbours");
  require(max_correction_step_m > 0.0 && max_correction_step_rad > 0.0, "max_correction_step_m/rad", "> 0");
  require(max_fitness_m2 > 0.0, "max_fitness_m2", "> 0");
  require(min_constraining_fraction >= 0.0 && min_constraining_fraction < 1.0, "min_constraining_fraction",
          "in [0, 1)");
}

Eigen::Matrix3d planar_information(const GicpCloud& source, const GicpCloud& target, const SE3& T_target_source,
                                   const Eigen::Vector3d& pivot, double max_correspondence_m) {
  std::vector<std::uint32_t> matches(source.size(), kGicpNoMatch);
  if (!target.index.empty()) {
    const auto bound_sq = static_cast<float>(max_correspondence_m * max_correspondence_m);
    for (std::size_t i = 0; i < source.size(); ++i) {
      float d2 = 0.0f;
      const Eigen::Vector3d p = T_target_source * source.points[i].cast<double>();
      if (!target.index.nearest(p.cast<float>(), bound_sq, matches[i], d2)) matches[i] = kGicpNoMatch;
    }
  }
  return planar_information(source, target, T_target_source, pivot, matches);
}

Eigen::Matrix3d planar_information(const GicpCloud& source, const GicpCloud& target, const SE3& T_target_source,
                                   const Eigen::Vector3d& pivot, const std::vector<std::uint32_t>& matches) {
  if (matches.size() != source.size()) throw Error("planar_information: one match entry per source point expected");
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  const Eigen::Matrix3d R = T_target_source.rotation();
  for (std::size_t i = 0; i < source.size(); ++i) {
    const std::uint32_t j = matches[i];
    if (j == kGicpNoMatch) continue;
    if (j >= target.size() || j >= target.covariances.size() || i >= source.covariances.size())
      throw Error("planar_information: a match names no target point");
    const Eigen::Vector3d p = T_target_source * source.points[i].cast<double>();
    const Eigen::Matrix3d C =
        target.covariances[j].cast<double>() + R * source.covariances[i].cast<double>() * R.transpose();
    Eigen::Matrix<double, 3, 3> J;  // d p / d (x, y, yaw about the pivot)
    J << 1.0, 0.0, -(p.y() - pivot.y()), 0.0, 1.0, p.x() - pivot.x(), 0.0, 0.0, 0.0;
    H.noalias() += J.transpose() * C.inverse() * J;
  }
  return H;
}

CorrectedOdometry::CorrectedOdometry(CorrectedOdometryParams p, const SE3& T_base_sensor)
    : p_(std::move(p)), T_base_sensor_(T_base_sensor) {
  p_.validate();
  require(T_base_sensor.matrix().allFinite(), "T_base_sensor", "a finite transform");
}

void CorrectedOdometry::reset() {
  T_corr_ = SE3::Identity();
  previous_.reset();
}

SE3 CorrectedOdometry::constrained_correction(const GicpCloud& current, const SE3& T_odom_base,
                                              const std::vector<std::uint32_t>& pairs, CorrectionUpdate& u) const {
  // Directions of (x, y, yaw) that the matched surfaces hardly constrain (a corridor's walls say
  // nothing about the position along it; a 5 cm riser seen by a few points barely does) keep the
  // kinematic odometry: GICP moves freely along them with the noise of the depth images, by
  // centimetres per view, while the legs drift by millimetres per step. Per match, a direction
  // has information 0.5 from a plane it runs along and 1 / (2 epsilon) from a plane facing it.
  const Eigen::Vector3d pivot = (T_corr_ * T_odom_base).translation();
  // GICP's own correspondences at its result (no second search).
  const Eigen::Matrix3d H = planar_information(current, *previous_, u.gicp.T_target_source, pivot, pairs);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(H);
  const double matches = static_cast<double>(std::max<std::size_t>(u.gicp.correspondences, 1));
  const double facing = 1.0 / (2.0 * p_.gicp.covariance_epsilon);
  const double min_info = matches * (0.5 + p_.min_constraining_fraction * (facing - 0.5));
  // The update as a planar motion of the map frame about the pivot: p -> R(yaw) (p - c) + c + d.
  const SE3 left = u.gicp.T_target_source * T_corr_.inverse();
  const Pose2 left2 = pose2_from_se3(left);
  const Eigen::Vector2d c = pivot.head<2>();
  const Eigen::Vector2d d = Eigen::Vector2d(left2.x, left2.y) + Eigen::Rotation2Dd(left2.theta) * c - c;
  const Eigen::Vector3d s(d.x(), d.y(), left2.theta);
  Eigen::Vector3d kept = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    if (es.eigenvalues()(k) >= min_info)
      kept += es.eigenvectors().col(k) * es.eigenvectors().col(k).dot(s);
    else
      ++u.degenerate_directions;
  }
  if (u.degenerate_directions == 0) return u.gicp.T_target_source;
  const Eigen::Vector2d t = c + kept.head<2>() - Eigen::Rotation2Dd(kept.z()) * c;
  return se3_from_pose2(Pose2{t.x(), t.y(), kept.z()}) * T_corr_;
}

CorrectionUpdate CorrectedOdometry::update(const SE3& T_odom_base, const PointCloud& cloud_sensor) {
  CorrectionUpdate u;
  u.T_corr = T_corr_;
  u.T_corrected_base = T_corr_ * T_odom_base;
  if (!T_odom_base.matrix().allFinite()) {
    u.reason = "odometry pose is not finite";
    u.T_corrected_base = T_corr_;
    return u;
  }
  // The ground band is cut in the odometry frame, whose height comes from the leg kinematics and
  // does not drift: every view then keeps the same surfaces. Cut in the base frame, a robot on a
  // 5 cm stair drops the riser of the next one that it kept from the floor, and matching the
  // two partial risers pulls the correction along the walk.
  const SE3 T_odom_sensor = T_odom_base * T_base_sensor_;
  const PointCloud cloud = remove_ground(cloud_sensor, T_odom_sensor, p_.ground_band_m);
  if (cloud.size() < p_.min_points) {
    u.reason = "too few points after ground removal (" + std::to_string(cloud.size()) + ")";
    return u;
  }
  const GicpCloud current = transform_gicp_cloud(prepare_gicp_cloud(cloud, p_.gicp), T_odom_sensor);  // T_odom^t p_i
  if (!previous_) {
    previous_ = transform_gicp_cloud(current, T_corr_);
    u.reason = "first cloud";
    return u;
  }
  std::vector<std::uint32_t> matches;
  u.gicp = gicp_align(current, *previous_, T_corr_, p_.gicp, &matches);
  const SE3 step = T_corr_.inverse() * u.gicp.T_target_source;
  const bool small = step.translation().norm() <= p_.max_correction_step_m &&
                     Eigen::AngleAxisd(step.rotation()).angle() <= p_.max_correction_step_rad;
  if (!u.gicp.T_target_source.matrix().allFinite() || !small || u.gicp.fitness > p_.max_fitness_m2) {
    u.reason = !small ? "GICP correction step too large, rejected" : "GICP fitness too poor, rejected";
  } else {
    T_corr_ = constrained_correction(current, T_odom_base, matches, u);
    u.corrected = true;
  }
  u.T_corr = T_corr_;
  u.T_corrected_base = T_corr_ * T_odom_base;
  previous_ = transform_gicp_cloud(current, T_corr_);
  return u;
}

}  // namespace bipednav::localization
