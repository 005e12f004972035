#pragma once

#include <Eigen/Core>
#include <optional>

#include "bipednav/tracking/imm_cv_ct.hpp"
#include "bipednav/tracking/kalman_cv.hpp"
#include "bipednav/tracking/tracker_params.hpp"

namespace bipednav::tracking {

// A track's state estimate under TrackerParams::motion_model: the constant-velocity Kalman filter
// or the IMM of constant velocity and coordinated turn. Position measurements only.
class TrackFilter {
 public:
  // Started at position z (covariance R) with zero velocity (initial_speed_std_mps).
  TrackFilter(const Eigen::Vector2d& z, const Eigen::Matrix2d& R, const TrackerParams& params);

  void predict(double dt_s);  // dt_s > 0
  // The innovation of a measurement against the current (predicted) estimate, for gating.
  Innovation innovation(const Eigen::Vector2d& z, const Eigen::Matrix2d& R) const;
  void update(const Eigen::Vector2d& z, const Eigen::Matrix2d& R);
  void miss();  // a cycle without a measurement

  // (x, y, vx, vy) and its covariance.
  Eigen::Vector4d state() const;
  Eigen::Matrix4d covariance() const;
  // The position dt_s (>= 0) ahead and its covariance, the propagated state covariance's position
  // block (without further measurements it grows with the process noise).
  void predict_position(double dt_s, Eigen::Vector2d& mean, Eigen::Matrix2d& cov) const;
  // The IMM's probability of the coordinated turn (0 for the constant-velocity filter).
  double turn_probability() const { return imm_ ? imm_->mode_probabilities()[1] : 0.0; }

 private:
  double accel_psd_;
  Eigen::Vector4d x_ = Eigen::Vector4d::Zero();  // constant velocity
  Eigen::Matrix4d P_ = Eigen::Matrix4d::Identity();
  std::optional<ImmCvCt> imm_;  // the IMM instead
};

}  // namespace bipednav::tracking
