#include "bipednav/tracking/kalman_cv.hpp"

namespace bipednav::tracking {

Eigen::Matrix4d cv_transition(double dt_s) {
  Eigen::Matrix4d F = Eigen::Matrix4d::Identity();
  F(0, 2) = F(1, 3) = dt_s;
  return F;
}

Eigen::Matrix4d cv_process_noise(double dt_s, double accel_psd_m2ps3) {
  const double t = dt_s, q = accel_psd_m2ps3;
  const double pp = q * t * t * t / 3.0, pv = q * t * t / 2.0, vv = q * t;
  Eigen::Matrix4d Q = Eigen::Matrix4d::Zero();
  Q(0, 0) = Q(1, 1) = pp;
  Q(0, 2) = Q(2, 0) = Q(1, 3) = Q(3, 1) = pv;
  Q(2, 2) = Q(3, 3) = vv;
  return Q;
}

void cv_predict(Eigen::Vector4d& x, Eigen::Matrix4d& P, double dt_s, double accel_psd_m2ps3) {
  const Eigen::Matrix4d F = cv_transition(dt_s);
  x = F * x;
  P = F * P * F.transpose() + cv_process_noise(dt_s, accel_psd_m2ps3);
}

}  // namespace bipednav::tracking
