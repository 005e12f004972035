#pragma once

#include <Eigen/Core>
#include <Eigen/LU>

namespace bipednav::tracking {

// A position measurement's innovation: nu = z - H x and its covariance S = H P H^T + R, with
// H = [I2 0] (the state's first two components are the position).
struct Innovation {
  Eigen::Vector2d nu = Eigen::Vector2d::Zero();
  Eigen::Matrix2d S = Eigen::Matrix2d::Identity();
  // nu^T S^-1 nu: the squared Mahalanobis distance (chi-square with 2 dof for a true detection).
  double mahalanobis2() const { return nu.dot(S.inverse() * nu); }
};

// Constant velocity on (x, y, vx, vy): x' = F x, F = [I T I; 0 I].
Eigen::Matrix4d cv_transition(double dt_s);
// Continuous white-noise acceleration of power spectral density q per axis over dt_s:
// Q = q [dt^3/3 dt^2/2; dt^2/2 dt] per axis (Bar-Shalom, Li, Kirubarajan 2001, eq. 6.2.2-12).
Eigen::Matrix4d cv_process_noise(double dt_s, double accel_psd_m2ps3);
// x <- F x, P <- F P F^T + Q.
void cv_predict(Eigen::Vector4d& x, Eigen::Matrix4d& P, double dt_s, double accel_psd_m2ps3);

template <int N>
Innovation position_innovation(const Eigen::Matrix<double, N, 1>& x, const Eigen::Matrix<double, N, N>& P,
                               const Eigen::Vector2d& z, const Eigen::Matrix2d& R) {
  return {z - x.template head<2>(), P.template topLeftCorner<2, 2>() + R};
}

// The Kalman update with a position measurement z of covariance R (H = [I2 0]), in Joseph form
// P = (I - K H) P (I - K H)^T + K R K^T, which stays symmetric positive definite under rounding.
template <int N>
void position_update(Eigen::Matrix<double, N, 1>& x, Eigen::Matrix<double, N, N>& P, const Eigen::Vector2d& z,
                     const Eigen::Matrix2d& R) {
  const Innovation in = position_innovation<N>(x, P, z, R);
  const Eigen::Matrix<double, N, 2> K = P.template leftCols<2>() * in.S.inverse();
  x += K * in.nu;
  Eigen::Matrix<double, N, N> I_KH = Eigen::Matrix<double, N, N>::Identity();
  I_KH.template leftCols<2>() -= K;
  P = I_KH * P * I_KH.transpose() + K * R * K.transpose();
  P = 0.5 * (P + P.transpose()).eval();
}

}  // namespace bipednav::tracking
