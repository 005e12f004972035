#pragma once

#include <Eigen/Core>
#include <array>

#include "bipednav/tracking/kalman_cv.hpp"
#include "bipednav/tracking/tracker_params.hpp"

namespace bipednav::tracking {

using Vector5d = Eigen::Matrix<double, 5, 1>;
using Matrix5d = Eigen::Matrix<double, 5, 5>;

// The coordinated turn on (x, y, vx, vy, omega) over dt_s: the velocity turns at the constant
// rate omega (Bar-Shalom, Li, Kirubarajan 2001, eq. 11.7.1-4), with its Jacobian F for the EKF
// (the limit omega -> 0 where the closed form divides by omega). Returns f(x).
Vector5d ct_transition(const Vector5d& x, double dt_s, Matrix5d* F);

// An interacting multiple model estimator (Blom and Bar-Shalom 1988; Bar-Shalom et al. 2001,
// sec. 11.6.6) of two models on the state (x, y, vx, vy, omega): 0 constant velocity (omega held
// at zero), 1 coordinated turn (EKF). The constant velocity's white acceleration is accel_psd_m2ps3,
// the turn's imm_turn_accel_psd_m2ps3 (the manoeuvring model: larger); the
// turn rate walks with turn_rate_psd_rad2ps3. The models switch as a Markov chain at
// imm_switch_rate_hz.
class ImmCvCt {
 public:
  // A new estimate at position z (covariance R), velocity zero with initial_speed_std_mps.
  ImmCvCt(const Eigen::Vector2d& z, const Eigen::Matrix2d& R, const TrackerParams& params);

  // Mixing and each model's prediction over dt_s (> 0); the combined prediction is state().
  void predict(double dt_s);
  // Each model's update with z, its likelihood reweighting the model probabilities.
  void update(const Eigen::Vector2d& z, const Eigen::Matrix2d& R);
  // No measurement: the prediction stands.
  void miss();

  // The models' moment-matched combination (x, y, vx, vy, omega).
  const Vector5d& state() const { return x_; }
  const Matrix5d& covariance() const { return P_; }
  const std::array<double, 2>& mode_probabilities() const { return mu_; }
  // The position dt_s ahead of the current estimate without further model switches: the
  // mixture's mean and covariance.
  void predict_position(double dt_s, Eigen::Vector2d& mean, Eigen::Matrix2d& cov) const;

 private:
  // Model m's prediction of (x, P) over dt_s.
  void predict_model(int m, Vector5d& x, Matrix5d& P, double dt_s) const;
  void combine();

  double accel_psd_, turn_accel_psd_, turn_psd_, switch_rate_hz_, omega_std_;
  std::array<Vector5d, 2> xm_;
  std::array<Matrix5d, 2> Pm_;
  std::array<double, 2> mu_{0.5, 0.5};
  Vector5d x_ = Vector5d::Zero();
  Matrix5d P_ = Matrix5d::Identity();
};

}  // namespace bipednav::tracking
