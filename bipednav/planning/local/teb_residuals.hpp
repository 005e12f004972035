#pragma once

// The residual blocks of the TEB objective (eq. 5.21) with the weights applied, in two forms: templated on
// the scalar (ceres::Jet for the Ceres solver and for checking derivatives, double for evaluation) and in
// double precision with analytic Jacobians, for the banded Levenberg-Marquardt solver (teb_lm). Both
// compute the same functions; tests/planning/local/teb_residuals_test.cpp checks the analytic Jacobians
// against automatic differentiation.

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <type_traits>
#include <vector>

#include "bipednav/common/twist.hpp"
#include "bipednav/planning/local/costmap_obstacles.hpp"
#include "bipednav/planning/local/teb_params.hpp"
#include "bipednav/planning/local/teb_terms.hpp"

namespace bipednav::planning::local {

// Weights of the residual blocks (squared into the objective); the outer iterations adapt nh and obstacle.
struct TebWeights {
  double nh, back, vel_x, vel_th, acc_x, acc_th, time, obstacle, via, dynamic_obstacle;
};

// A moving obstacle as the band sees it (TebOptimizerParams::dynamic_obstacles): its predicted centre
// at the band's start time, its velocity, its radius and the distance the robot's centre keeps from its
// centre (robot radius + radius + margin), growing by growth_mps per second of prediction. With lead_s > 0
// the obstacle at time t is the segment from its prediction at t to lead_s further along its velocity
// (the stretch it sweeps next), so a band passing in front of it keeps the bound from where it will be.
struct TebMovingObstacle {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();
  double radius_m = 0.0;
  double clearance_m = 0.0;
  double growth_mps = 0.0;
  double lead_s = 0.0;

  // Constant-velocity prediction t_s after the band's start.
  Eigen::Vector2d at(double t_s) const { return position + velocity * t_s; }
  // The end of the swept segment at t_s (at(t_s) without lead_s).
  Eigen::Vector2d lead_end(double t_s) const { return at(t_s + lead_s); }
  // The distance the robot's centre keeps from the (swept) prediction at t_s.
  double bound(double t_s) const { return clearance_m + growth_mps * t_s; }
  // Distance of p from the (swept) prediction at t_s.
  double distance(const Eigen::Vector2d& p, double t_s) const;
  bool usable() const {
    return position.allFinite() && velocity.allFinite() && std::isfinite(radius_m) && std::isfinite(clearance_m) &&
           clearance_m >= 0.0 && std::isfinite(growth_mps) && growth_mps >= 0.0 && std::isfinite(lead_s) &&
           lead_s >= 0.0;
  }
};

TebWeights base_weights(const TebOptimizerParams& p);

struct TebResidualContext {
  const TebLimits* limits;
  const TebOptimizerParams* params;
  const TebWeights* w;
};

// ---- Templated residual blocks (a, b, d: poses x, y, theta; dt: intervals) ----

// Terms between s_k and s_{k+1}: eq. 5.16 (non-holonomic), backwards penalty, eq. 5.13 (velocity limits,
// asymmetric forward/backward), eq. 5.4 (time). 5 residuals.
template <typename T>
void edge_residuals(const TebResidualContext& c, const T* a, const T* b, const T* dt, T* r) {
  using std::sqrt;
  const auto& L = *c.limits;
  const double eps = c.params->penalty_epsilon;
  // The headings' cosines and sines once for the three terms that use them.
  const Heading<T> ha = heading(a[2]), hb = heading(b[2]);
  const T dx = b[0] - a[0];
  const T dy = b[1] - a[1];
  const T v = linear_velocity(ha, dx, dy, dt[0], c.params->sign_gain);
  const T w = angular_velocity(a[2], b[2], dt[0]);
  r[0] = sqrt(c.w->nh) * nonholonomic_error(ha, hb, dx, dy);
  r[1] = sqrt(c.w->back) * backwards_error(ha, dx, dy);
  r[2] = sqrt(c.w->vel_x) * penalty_interval(v, -L.velocity.max_vel_x_backwards_mps, L.velocity.max_vel_x_mps, eps);
  r[3] = sqrt(c.w->vel_th) * penalty_symmetric(w, L.velocity.max_vel_theta_radps, eps);
  r[4] = sqrt(c.w->time) * time_error(dt[0]);
}

// eq. 5.11-5.12, 5.14 over s_k, s_{k+1}, s_{k+2}. 2 residuals.
template <typename T>
void acc_residuals(const TebResidualContext& c, const T* a, const T* b, const T* d, const T* dt1, const T* dt2, T* r) {
  using std::sqrt;
  const double eps = c.params->penalty_epsilon, g = c.params->sign_gain;
  const T v1 = linear_velocity(a[0], a[1], a[2], b[0], b[1], dt1[0], g);
  const T v2 = linear_velocity(b[0], b[1], b[2], d[0], d[1], dt2[0], g);
  const T w1 = angular_velocity(a[2], b[2], dt1[0]);
  const T w2 = angular_velocity(b[2], d[2], dt2[0]);
  r[0] = sqrt(c.w->acc_x) *
         penalty_symmetric(acceleration(v1, v2, dt1[0], dt2[0]), c.limits->velocity.acc_lim_x_mps2, eps);
  r[1] = sqrt(c.w->acc_th) *
         penalty_symmetric(acceleration(w1, w2, dt1[0], dt2[0]), c.limits->velocity.acc_lim_theta_radps2, eps);
}

// Acceleration of the first interval from the robot's current velocity v0. 2 residuals.
template <typename T>
void start_acc_residuals(const TebResidualContext& c, const Twist& v0, const T* a, const T* b, const T* dt, T* r) {
  using std::sqrt;
  const double eps = c.params->penalty_epsilon;
  const T v = linear_velocity(a[0], a[1], a[2], b[0], b[1], dt[0], c.params->sign_gain);
  const T w = angular_velocity(a[2], b[2], dt[0]);
  r[0] = sqrt(c.w->acc_x) * penalty_symmetric(T((v - T(v0.linear_x)) / dt[0]), c.limits->velocity.acc_lim_x_mps2, eps);
  r[1] = sqrt(c.w->acc_th) *
         penalty_symmetric(T((w - T(v0.angular_z)) / dt[0]), c.limits->velocity.acc_lim_theta_radps2, eps);
}

// eq. 5.15 / 5.19: one pose against one obstacle. 1 residual.
template <typename T>
T obstacle_residual(const TebResidualContext& c, const Obstacle& o, const T* p) {
  using std::sqrt;
  const double bound = c.limits->min_obstacle_dist_m, eps = c.params->penalty_epsilon;
  if constexpr (!std::is_same_v<T, double>) {
    // Most associated obstacles lie beyond the bound, where the penalty is T(0): decided on the distance's
    // scalar part (bitwise the Jet's, as penalty_below compares it) without its derivatives.
    if (!(jet_value_obstacle_distance(o, p[0].a, p[1].a) < bound + eps)) return sqrt(c.w->obstacle) * T(0.0);
  }
  const T d = obstacle_distance(o, p[0], p[1]);
  return sqrt(c.w->obstacle) * penalty_below(d, bound, eps);
}

// One pose at time t_s after the band's start against one moving obstacle's prediction (mirrors
// obstacle_residual, bound o.bound(t_s)). 1 residual.
template <typename T>
T dynamic_obstacle_residual(const TebResidualContext& c, const TebMovingObstacle& o, double t_s, const T* p) {
  using std::sqrt;
  if constexpr (!std::is_same_v<T, double>) {
    // Beyond the bound the penalty is T(0): decided on the distance's scalar part (as obstacle_residual).
    const double d = o.lead_s > 0.0 ? jet_value_distance_to_segment(p[0].a, p[1].a, o.at(t_s), o.lead_end(t_s))
                                    : jet_value_distance_to_point(p[0].a, p[1].a, o.at(t_s));
    if (!(d < o.bound(t_s) + c.params->penalty_epsilon)) return sqrt(c.w->dynamic_obstacle) * T(0.0);
  }
  const T d = o.lead_s > 0.0 ? distance_to_segment(p[0], p[1], o.at(t_s), o.lead_end(t_s))
                             : distance_to_point(p[0], p[1], o.at(t_s));
  return sqrt(c.w->dynamic_obstacle) * penalty_below(d, o.bound(t_s), c.params->penalty_epsilon);
}

// Via-point attraction. 2 residuals.
template <typename T>
void via_residuals(const TebResidualContext& c, const Eigen::Vector2d& via, const T* p, T* r) {
  using std::sqrt;
  const auto e = via_point_error(p[0], p[1], via);
  r[0] = sqrt(c.w->via) * e[0];
  r[1] = sqrt(c.w->via) * e[1];
}

// ---- Analytic Jacobians (double) ----

// Linear (eq. 5.8) and angular (eq. 5.9) velocity of one interval and their gradients with respect to
// (x1, y1, theta1, x2, y2, theta2, dt).
struct IntervalVelocity {
  double v = 0.0, w = 0.0;
  std::array<double, 7> dv{}, dw{};
};
IntervalVelocity interval_velocity(const double* a, const double* b, double dt, double sign_gain);
// The same with cos/sin of a's heading given (the solver computes them once per pose).
IntervalVelocity interval_velocity(const double* a, const double* b, double dt, double sign_gain, double cos_a,
                                   double sin_a);

// Row-major Jacobians: J[i * cols + j] = d r_i / d var_j.
// edge: vars (a[3], b[3], dt); 5 x 7.
void edge_jacobian(const TebResidualContext& c, const double* a, const double* b, double dt, const IntervalVelocity& iv,
                   double* r, double* J);
// The same with cos/sin of both headings given.
void edge_jacobian(const TebResidualContext& c, const double* a, const double* b, double dt, const IntervalVelocity& iv,
                   double cos_a, double sin_a, double cos_b, double sin_b, double* r, double* J);
// acc: vars (a[3], b[3], d[3], dt1, dt2); 2 x 11. iv1, iv2: the intervals a-b and b-d.
void acc_jacobian(const TebResidualContext& c, const IntervalVelocity& iv1, const IntervalVelocity& iv2, double dt1,
                  double dt2, double* r, double* J);
// start acc: vars (a[3], b[3], dt); 2 x 7.
void start_acc_jacobian(const TebResidualContext& c, const Twist& v0, const IntervalVelocity& iv, double dt, double* r,
                        double* J);
// dynamic_obstacle_residual and its gradient with respect to (x, y) of the pose (J: 2 entries).
double dynamic_obstacle_jacobian(const TebResidualContext& c, const TebMovingObstacle& o, double t_s, double x,
                                 double y, double* J);
// Distance of (x, y) to the obstacle (as obstacle_distance) and its gradient.
double obstacle_distance_gradient(const Obstacle& o, double x, double y, double* grad);

}  // namespace bipednav::planning::local
