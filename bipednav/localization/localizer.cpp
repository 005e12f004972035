#include "bipednav/localization/localizer.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace bipednav::localization {

void LocalizerParams::validate() const {
  require(method == "loam" || method == "odometry", "localization.method", "loam or odometry");
  require(sweep_duration_s > 0.0, "localization.sweep_duration_s", "> 0");
  require(max_correction_jump_m > 0.0, "localization.max_correction_jump_m", "> 0");
  require(max_correction_jump_rad > 0.0, "localization.max_correction_jump_rad", "> 0");
  require(unhealthy_after_bad_sweeps >= 1, "localization.unhealthy_after_bad_sweeps", ">= 1");
  require(odometry_timeout_s > 0.0, "localization.odometry_timeout_s", "> 0");
  require(max_odometry_speed_mps > 0.0, "localization.max_odometry_speed_mps", "> 0");
  require(max_odometry_rate_radps > 0.0, "localization.max_odometry_rate_radps", "> 0");
  require(std::isfinite(odometry_drift_ratio) && odometry_drift_ratio >= 0.0, "localization.odometry_drift_ratio",
          ">= 0");
  require(std::isfinite(scan_position_sigma_m) && scan_position_sigma_m > 0.0, "localization.scan_position_sigma_m",
          "> 0");
  loam.validate();
}

Localizer::Localizer(LocalizerParams params, const RobotProfile& robot, const Pose2& T_map_base_initial)
    : params_(std::move(params)), correction_(T_map_base_initial) {
  params_.validate();
  position_deviation_ = params_.scan_position_sigma_m * Eigen::Matrix2d::Identity();
  if (const SensorMount* lidar = robot.lidar()) {
    T_base_lidar_ = lidar->T_base_sensor();
    has_lidar_ = true;
  }
  if (params_.method == "loam" && has_lidar_) {
    LoamParams lp = params_.loam;
    lp.output_deskewed = false;  // only the pose is read
    loam_ = std::make_unique<Loam>(std::move(lp));
  }
}

void Localizer::reset(const Pose2& T_map_base) {
  correction_ = T_map_base * odom_now_.inverse();
  position_deviation_ = params_.scan_position_sigma_m * Eigen::Matrix2d::Identity();
  anchored_ = false;
  prev_sweep_odom_.reset();
  bad_sweeps_ = 0;
  if (loam_) loam_->reset();
}

void Localizer::add_odometry(const Odometry& odom) {
  if (!odom.T_odom_base.is_finite() || !odom.velocity.is_finite()) {
    reason_ = "odometry is not finite";
    return;
  }
  // Out-of-order or repeated stamps are dropped: the history must stay sorted.
  if (!history_.empty() && odom.stamp_s <= history_.back().stamp_s) return;
  if (!history_.empty()) {
    const Pose2 step = history_.back().T_odom_base.inverse() * odom.T_odom_base;
    position_deviation_ += params_.odometry_drift_ratio * std::hypot(step.x, step.y) * Eigen::Matrix2d::Identity();
  }
  history_.push_back(odom);
  while (history_.size() > 2 && history_.front().stamp_s < odom.stamp_s - 2.0) history_.pop_front();
  odom_now_ = odom.T_odom_base;
  velocity_ = odom.velocity;
  last_odom_s_ = odom.stamp_s;
}

std::optional<Pose2> Localizer::odom_at(double t_s) const {
  if (history_.empty() || t_s < history_.front().stamp_s - 1e-9) return std::nullopt;
  for (std::size_t i = 1; i < history_.size(); ++i) {
    const Odometry& a = history_[i - 1];
    const Odometry& b = history_[i];
    if (t_s <= b.stamp_s) {
      const double s = (t_s - a.stamp_s) / std::max(1e-9, b.stamp_s - a.stamp_s);
      const Pose2 d = a.T_odom_base.inverse() * b.T_odom_base;
      return a.T_odom_base * Pose2{s * d.x, s * d.y, s * d.theta};
    }
  }
  // Slightly past the newest sample: hold it (the sweep end and the step end coincide).
  if (t_s <= history_.back().stamp_s + 0.05) return history_.back().T_odom_base;
  return std::nullopt;
}

void Localizer::add_sweep(const PointCloud& sweep) {
  if (!loam_) return;
  const double t_end = sweep.stamp_s + params_.sweep_duration_s;
  const auto odom_end = odom_at(t_end);
  if (!odom_end) {
    reason_ = "no odometry at the sweep's end";
    ++bad_sweeps_;
    return;
  }
  const SE3 T_lidar_base = T_base_lidar_.inverse();
  if (!anchored_) {
    loam_->reset();
    loam_->set_pose(se3_from_pose2(correction_ * *odom_end) * T_base_lidar_);
    anchored_ = true;
  }
  std::optional<SE3> prior;
  bool odometry_jumped = false;
  if (prev_sweep_odom_) {
    const Pose2 delta = prev_sweep_odom_->inverse() * *odom_end;
    odometry_jumped = !plausible_odometry_motion(delta, t_end - prev_sweep_end_s_);
    if (!odometry_jumped) prior = T_lidar_base * se3_from_pose2(delta) * T_base_lidar_;
  }
  prev_sweep_odom_ = *odom_end;
  prev_sweep_end_s_ = t_end;
  // The IMU's gravity direction holds LOAM's roll and pitch (odometry samples carry the tilt).
  const Odometry& imu = history_.back();
  const Eigen::Vector3d up_in_lidar = T_base_lidar_.linear().transpose() *
                                      rpy_to_matrix(imu.roll_rad, imu.pitch_rad, 0.0).transpose() *
                                      Eigen::Vector3d::UnitZ();
  const LoamOutput out = loam_->process(sweep, prior, up_in_lidar);
  const Pose2 predicted = correction_ * *odom_end;
  const Pose2 measured = pose2_from_se3(out.T_world_lidar * T_lidar_base);
  bool jump = distance(predicted, measured) > params_.max_correction_jump_m ||
              std::abs(angle_diff(predicted.theta, measured.theta)) > params_.max_correction_jump_rad;
  if (jump && odometry_jumped && out.healthy && measured.is_finite()) {
    // The odometry jumped, LOAM did not: the map pose stays LOAM's, the correction absorbs the jump.
    ++odometry_jumps_;
    jump = false;
  }
  if (!out.healthy || !measured.is_finite() || jump) {
    reason_ = !out.healthy ? "LOAM: " + out.reason : (jump ? "LOAM pose jumped away from odometry" : "LOAM pose NaN");
    ++bad_sweeps_;
    if (jump) {  // re-anchor LOAM on the odometry prediction rather than trusting either blindly
      loam_->set_pose(se3_from_pose2(predicted) * T_base_lidar_);
    }
    return;
  }
  bad_sweeps_ = 0;
  reason_.clear();
  correction_ = measured * odom_end->inverse();
  // The map match fixed the directions it observed; the others keep the odometry's uncertainty.
  const Eigen::Matrix2d& weak = out.unobserved_xy;
  const Eigen::Matrix2d observed = Eigen::Matrix2d::Identity() - weak;
  position_deviation_ = weak * position_deviation_ * weak + params_.scan_position_sigma_m * observed;
}

double Localizer::position_sigma_m(const Eigen::Vector2d& direction_map) const {
  const double n = direction_map.norm();
  if (!(n > 0.0)) return weakest_position_sigma_m();
  const Eigen::Vector2d u = direction_map / n;
  return u.dot(position_deviation_ * u);
}

double Localizer::weakest_position_sigma_m(Eigen::Vector2d* direction_map) const {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(position_deviation_);
  if (direction_map) *direction_map = es.eigenvectors().col(1);
  return es.eigenvalues()(1);
}

bool Localizer::plausible_odometry_motion(const Pose2& delta, double dt_s) const {
  constexpr double kSlack_m = 0.05, kSlack_rad = 0.05;  // odometry noise over one sweep
  const double dt = std::max(dt_s, 0.0);
  return std::hypot(delta.x, delta.y) <= params_.max_odometry_speed_mps * dt + kSlack_m &&
         std::abs(delta.theta) <= params_.max_odometry_rate_radps * dt + kSlack_rad;
}

bool Localizer::healthy(double now_s) const {
  if (last_odom_s_ < 0.0 || now_s - last_odom_s_ > params_.odometry_timeout_s) return false;
  return bad_sweeps_ < params_.unhealthy_after_bad_sweeps;
}

}  // namespace bipednav::localization
