#include "bipednav/localization/corrected_odometry.hpp"

#include "bipednav/common/error.hpp"

namespace bipednav::localization {

void CorrectedOdometryParams::validate() const {
  gicp.validate();
  require(ground_band_m >= 0.0, "ground_band_m", ">= 0");
  require(min_points >= static_cast<std::size_t>(gicp.covariance_neighbours), "min_points",
          ">= gicp.covariance_neighbours");
  require(max_correction_step_m > 0.0 && max_correction_step_rad > 0.0, "max_correction_step_m/rad", "> 0");
  require(max_fitness_m2 > 0.0, "max_fitness_m2", "> 0");
}

SE3 kinematic_pose(const Odometry& odom, double z_m) {
  return make_se3(odom.T_odom_base.x, odom.T_odom_base.y, z_m, odom.roll_rad, odom.pitch_rad, odom.T_odom_base.theta);
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

CorrectionUpdate CorrectedOdometry::update(const SE3& T_odom_base, const PointCloud& cloud_sensor) {
  CorrectionUpdate u;
  u.T_corr = T_corr_;
  u.T_corrected_base = T_corr_ * T_odom_base;
  if (!T_odom_base.matrix().allFinite()) {
    u.reason = "odometry pose is not finite";
    u.T_corrected_base = T_corr_;
    return u;
  }
  const PointCloud cloud = remove_ground(cloud_sensor, T_base_sensor_, p_.ground_band_m);
  if (cloud.size() < p_.min_points) {
    u.reason = "too few points after ground removal (" + std::to_string(cloud.size()) + ")";
    return u;
  }
  const SE3 T_odom_sensor = T_odom_base * T_base_sensor_;
  const GicpCloud current = transform_gicp_cloud(prepare_gicp_cloud(cloud, p_.gicp), T_odom_sensor);  // T_odom^t p_i
  if (!previous_) {
    previous_ = transform_gicp_cloud(current, T_corr_);
    u.reason = "first cloud";
    return u;
  }
  u.gicp = gicp_align(current, *previous_, T_corr_, p_.gicp);
  const SE3 step = T_corr_.inverse() * u.gicp.T_target_source;
  const bool small = step.translation().norm() <= p_.max_correction_step_m &&
                     Eigen::AngleAxisd(step.rotation()).angle() <= p_.max_correction_step_rad;
  if (!u.gicp.T_target_source.matrix().allFinite() || !small || u.gicp.fitness > p_.max_fitness_m2) {
    u.reason = !small ? "GICP correction step too large, rejected" : "GICP fitness too poor, rejected";
  } else {
    T_corr_ = u.gicp.T_target_source;
    u.corrected = true;
  }
  u.T_corr = T_corr_;
  u.T_corrected_base = T_corr_ * T_odom_base;
  previous_ = transform_gicp_cloud(current, T_corr_);
  return u;
}

}  // namespace bipednav::localization
