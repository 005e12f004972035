#include "bipednav/tracking/track_filter.hpp"

namespace bipednav::tracking {

TrackFilter::TrackFilter(const Eigen::Vector2d& z, const Eigen::Matrix2d& R, const TrackerParams& params)
    : accel_psd_(params.accel_psd_m2ps3) {
  if (params.model() == MotionModel::kImmCvCt) {
    imm_.emplace(z, R, params);
    return;
  }
  x_.head<2>() = z;
  P_.setZero();
  P_.topLeftCorner<2, 2>() = R;
  P_(2, 2) = P_(3, 3) = params.initial_speed_std_mps * params.initial_speed_std_mps;
}

void TrackFilter::predict(double dt_s) {
  if (imm_)
    imm_->predict(dt_s);
  else
    cv_predict(x_, P_, dt_s, accel_psd_);
}

Innovation TrackFilter::innovation(const Eigen::Vector2d& z, const Eigen::Matrix2d& R) const {
  if (imm_) return position_innovation<5>(imm_->state(), imm_->covariance(), z, R);
  return position_innovation<4>(x_, P_, z, R);
}

void TrackFilter::update(const Eigen::Vector2d& z, const Eigen::Matrix2d& R) {
  if (imm_)
    imm_->update(z, R);
  else
    position_update<4>(x_, P_, z, R);
}

void TrackFilter::miss() {
  if (imm_) imm_->miss();
}

Eigen::Vector4d TrackFilter::state() const { return imm_ ? Eigen::Vector4d(imm_->state().head<4>()) : x_; }

Eigen::Matrix4d TrackFilter::covariance() const {
  return imm_ ? Eigen::Matrix4d(imm_->covariance().topLeftCorner<4, 4>()) : P_;
}

void TrackFilter::predict_position(double dt_s, Eigen::Vector2d& mean, Eigen::Matrix2d& cov) const {
  if (imm_) {
    imm_->predict_position(dt_s, mean, cov);
    return;
  }
  Eigen::Vector4d x = x_;
  Eigen::Matrix4d P = P_;
  if (dt_s > 0.0) cv_predict(x, P, dt_s, accel_psd_);
  mean = x.head<2>();
  cov = P.topLeftCorner<2, 2>();
}

}  // namespace bipednav::tracking
