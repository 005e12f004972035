#include "bipednav/tracking/imm_cv_ct.hpp"

#include <cmath>
#include <numbers>

namespace bipednav::tracking {

namespace {

// Below this turn rate the closed forms lose their digits to cancellation; their series do not.
constexpr double kSmallTurnRadps = 1e-3;

// N(nu; 0, S): the model likelihood of an innovation.
double gaussian_likelihood(const Innovation& in) {
  const double det = in.S.determinant();
  if (!(det > 0.0)) return 0.0;
  return std::exp(-0.5 * in.mahalanobis2()) / (2.0 * std::numbers::pi * std::sqrt(det));
}

}  // namespace

Vector5d ct_transition(const Vector5d& x, double dt_s, Matrix5d* F) {
  const double T = dt_s, w = x(4), vx = x(2), vy = x(3);
  const double s = std::sin(w * T), c = std::cos(w * T);
  // a = sin(wT)/w, b = (1 - cos(wT))/w and their derivatives in w (Taylor series near w = 0).
  double a, b, da, db;
  if (std::abs(w) < kSmallTurnRadps) {
    const double T2 = T * T, T3 = T2 * T, w2 = w * w;
    a = T - w2 * T3 / 6.0, b = 0.5 * w * T2 - w2 * w * T2 * T2 / 24.0;
    da = -w * T3 / 3.0 + w2 * w * T3 * T2 / 30.0, db = 0.5 * T2 - w2 * T2 * T2 / 8.0;
  } else {
    a = s / w, b = (1.0 - c) / w, da = (T * c * w - s) / (w * w), db = (T * s * w - (1.0 - c)) / (w * w);
  }
  Vector5d out;
  out << x(0) + a * vx - b * vy, x(1) + b * vx + a * vy, c * vx - s * vy, s * vx + c * vy, w;
  if (F != nullptr) {
    *F = Matrix5d::Identity();
    (*F)(0, 2) = a, (*F)(0, 3) = -b, (*F)(0, 4) = da * vx - db * vy;
    (*F)(1, 2) = b, (*F)(1, 3) = a, (*F)(1, 4) = db * vx + da * vy;
    (*F)(2, 2) = c, (*F)(2, 3) = -s, (*F)(2, 4) = -T * s * vx - T * c * vy;
    (*F)(3, 2) = s, (*F)(3, 3) = c, (*F)(3, 4) = T * c * vx - T * s * vy;
  }
  return out;
}

ImmCvCt::ImmCvCt(const Eigen::Vector2d& z, const Eigen::Matrix2d& R, const TrackerParams& params)
    : accel_psd_(params.accel_psd_m2ps3),
      turn_accel_psd_(params.imm_turn_accel_psd_m2ps3),
      turn_psd_(params.turn_rate_psd_rad2ps3),
      switch_rate_hz_(params.imm_switch_rate_hz),
      omega_std_(params.initial_turn_rate_std_radps) {
  Vector5d x = Vector5d::Zero();
  x.head<2>() = z;
  Matrix5d P = Matrix5d::Zero();
  P.topLeftCorner<2, 2>() = R;
  P(2, 2) = P(3, 3) = params.initial_speed_std_mps * params.initial_speed_std_mps;
  P(4, 4) = omega_std_ * omega_std_;
  xm_ = {x, x};
  Pm_ = {P, P};
  combine();
}

void ImmCvCt::predict_model(int m, Vector5d& x, Matrix5d& P, double dt_s) const {
  Matrix5d F = Matrix5d::Zero();
  Matrix5d Q = Matrix5d::Zero();
  Q.topLeftCorner<4, 4>() = cv_process_noise(dt_s, m == 0 ? accel_psd_ : turn_accel_psd_);
  if (m == 0) {
    // Constant velocity; its turn rate is zero with the prior's spread (so mixing into the turn
    // model neither claims nor forgets a turn it does not model).
    F.topLeftCorner<4, 4>() = cv_transition(dt_s);
    x = F * x;
    Q(4, 4) = omega_std_ * omega_std_;
  } else {
    x = ct_transition(x, dt_s, &F);
    Q(4, 4) = turn_psd_ * dt_s;
  }
  P = F * P * F.transpose() + Q;
}

void ImmCvCt::predict(double dt_s) {
  // Mixing (Bar-Shalom et al. 2001, eq. 11.6.6-6 to -10): the chance of each switch over dt_s,
  // the predicted model probabilities c_j and each model's mixed prior.
  const double p = 1.0 - std::exp(-switch_rate_hz_ * dt_s);
  const double pi[2][2] = {{1.0 - p, p}, {p, 1.0 - p}};
  std::array<Vector5d, 2> x0;
  std::array<Matrix5d, 2> P0;
  for (int j = 0; j < 2; ++j) {
    const double cj = pi[0][j] * mu_[0] + pi[1][j] * mu_[1];
    x0[j].setZero();
    for (int i = 0; i < 2; ++i) x0[j] += (pi[i][j] * mu_[i] / cj) * xm_[i];
    P0[j].setZero();
    for (int i = 0; i < 2; ++i) {
      const Vector5d d = xm_[i] - x0[j];
      P0[j] += (pi[i][j] * mu_[i] / cj) * (Pm_[i] + d * d.transpose());
    }
  }
  const double c0 = pi[0][0] * mu_[0] + pi[1][0] * mu_[1];
  mu_ = {c0, 1.0 - c0};
  for (int j = 0; j < 2; ++j) {
    predict_model(j, x0[j], P0[j], dt_s);
    xm_[j] = x0[j];
    Pm_[j] = P0[j];
  }
  combine();
}

void ImmCvCt::update(const Eigen::Vector2d& z, const Eigen::Matrix2d& R) {
  std::array<double, 2> weight{};
  for (int j = 0; j < 2; ++j) {
    weight[j] = mu_[j] * gaussian_likelihood(position_innovation<5>(xm_[j], Pm_[j], z, R));
    position_update<5>(xm_[j], Pm_[j], z, R);
  }
  const double total = weight[0] + weight[1];
  // Both likelihoods underflow only for a measurement far outside both gates: keep the priors.
  if (total > 0.0 && std::isfinite(total)) mu_ = {weight[0] / total, weight[1] / total};
  combine();
}

void ImmCvCt::miss() { combine(); }

void ImmCvCt::combine() {
  x_ = mu_[0] * xm_[0] + mu_[1] * xm_[1];
  P_.setZero();
  for (int j = 0; j < 2; ++j) {
    const Vector5d d = xm_[j] - x_;
    P_ += mu_[j] * (Pm_[j] + d * d.transpose());
  }
}

void ImmCvCt::predict_position(double dt_s, Eigen::Vector2d& mean, Eigen::Matrix2d& cov) const {
  std::array<Vector5d, 2> x = xm_;
  std::array<Matrix5d, 2> P = Pm_;
  if (dt_s > 0.0)
    for (int j = 0; j < 2; ++j) predict_model(j, x[j], P[j], dt_s);
  mean = mu_[0] * x[0].head<2>() + mu_[1] * x[1].head<2>();
  cov.setZero();
  for (int j = 0; j < 2; ++j) {
    const Eigen::Vector2d d = x[j].head<2>() - mean;
    cov += mu_[j] * (P[j].topLeftCorner<2, 2>() + d * d.transpose());
  }
}

}  // namespace bipednav::tracking
