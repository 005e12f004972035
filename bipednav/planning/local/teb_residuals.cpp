#include "bipednav/planning/local/teb_residuals.hpp"

namespace bipednav::planning::local {

namespace {

// Derivative of penalty_interval(v, lower, upper, eps) with respect to v (0 inside, as the Jets give).
double penalty_interval_slope(double v, double lower, double upper, double eps) {
  if (v < lower + eps) return -1.0;
  if (v > upper - eps) return 1.0;
  return 0.0;
}

double penalty_symmetric_slope(double v, double bound, double eps) {
  return penalty_interval_slope(v, -bound, bound, eps);
}

// distance_to_point with its gradient.
double point_distance_gradient(double px, double py, const Eigen::Vector2d& c, double* grad) {
  const double ex = px - c.x(), ey = py - c.y();
  const double n = safe_norm(ex, ey);
  grad[0] = ex / n;
  grad[1] = ey / n;
  return n;
}

// distance_to_segment with its gradient (through the projection parameter t while it is not clamped).
double segment_distance_gradient(double px, double py, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                 double* grad) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  if (len2 < 1e-18) return point_distance_gradient(px, py, a, grad);
  double t = ((px - a.x()) * ab.x() + (py - a.y()) * ab.y()) / len2;
  bool clamped = false;
  if (t < 0.0) t = 0.0, clamped = true;
  if (t > 1.0) t = 1.0, clamped = true;
  const double ex = px - (a.x() + t * ab.x()), ey = py - (a.y() + t * ab.y());
  const double n = safe_norm(ex, ey);
  if (clamped) {
    grad[0] = ex / n;
    grad[1] = ey / n;
  } else {
    const double along = (ex * ab.x() + ey * ab.y()) / len2;  // 0 up to rounding
    grad[0] = (ex - along * ab.x()) / n;
    grad[1] = (ey - along * ab.y()) / n;
  }
  return n;
}

}  // namespace

TebWeights base_weights(const TebOptimizerParams& p) {
  return {p.weight_kinematics_nh, p.weight_backwards,       p.weight_max_vel_x,   p.weight_max_vel_theta,
          p.weight_acc_lim_x,     p.weight_acc_lim_theta,   p.weight_optimaltime, p.weight_obstacle,
          p.weight_viapoint,      p.weight_dynamic_obstacle};
}

IntervalVelocity interval_velocity(const double* a, const double* b, double dt, double sign_gain) {
  return interval_velocity(a, b, dt, sign_gain, std::cos(a[2]), std::sin(a[2]));
}

IntervalVelocity interval_velocity(const double* a, const double* b, double dt, double sign_gain, double c1,
                                   double s1) {
  IntervalVelocity iv;
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  const double forward = c1 * dx + s1 * dy;
  const double n = safe_norm(dx, dy);
  const double g = sign_gain * forward;
  const double den = 1.0 + std::abs(g);
  const double sg = g / den;
  const double dsg = sign_gain / (den * den);  // d sg / d forward
  iv.v = n / dt * sg;
  const double k_n = sg / dt / n;   // d v / d n, divided by n (dn/ddx = dx / n)
  const double k_f = n / dt * dsg;  // d v / d forward
  iv.dv[0] = -k_n * dx - k_f * c1;
  iv.dv[1] = -k_n * dy - k_f * s1;
  iv.dv[2] = k_f * (-s1 * dx + c1 * dy);
  iv.dv[3] = k_n * dx + k_f * c1;
  iv.dv[4] = k_n * dy + k_f * s1;
  iv.dv[5] = 0.0;
  iv.dv[6] = -iv.v / dt;
  iv.w = angular_velocity(a[2], b[2], dt);
  iv.dw = {0.0, 0.0, -1.0 / dt, 0.0, 0.0, 1.0 / dt, -iv.w / dt};
  return iv;
}

void edge_jacobian(const TebResidualContext& c, const double* a, const double* b, double dt, const IntervalVelocity& iv,
                   double* r, double* J) {
  edge_jacobian(c, a, b, dt, iv, std::cos(a[2]), std::sin(a[2]), std::cos(b[2]), std::sin(b[2]), r, J);
}

void edge_jacobian(const TebResidualContext& c, const double* a, const double* b, double dt, const IntervalVelocity& iv,
                   double c1, double s1, double c2, double s2, double* r, double* J) {
  const auto& L = *c.limits;
  const double eps = c.params->penalty_epsilon;
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  for (int i = 0; i < 35; ++i) J[i] = 0.0;
  // Non-holonomic: h = (c1 + c2) dy - (s1 + s2) dx.
  const double wn = std::sqrt(c.w->nh);
  r[0] = wn * ((c1 + c2) * dy - (s1 + s2) * dx);
  J[0] = wn * (s1 + s2);
  J[1] = -wn * (c1 + c2);
  J[2] = wn * (-s1 * dy - c1 * dx);
  J[3] = -wn * (s1 + s2);
  J[4] = wn * (c1 + c2);
  J[5] = wn * (-s2 * dy - c2 * dx);
  // Backwards: max{0, -forward}.
  const double wb = std::sqrt(c.w->back);
  const double forward = c1 * dx + s1 * dy;
  r[1] = wb * penalty_below(forward, 0.0, 0.0);
  if (forward < 0.0) {
    J[7 + 0] = wb * c1;
    J[7 + 1] = wb * s1;
    J[7 + 2] = -wb * (-s1 * dx + c1 * dy);
    J[7 + 3] = -wb * c1;
    J[7 + 4] = -wb * s1;
  }
  // Velocity limits.
  const double wv = std::sqrt(c.w->vel_x);
  r[2] = wv * penalty_interval(iv.v, -L.velocity.max_vel_x_backwards_mps, L.velocity.max_vel_x_mps, eps);
  const double sv =
      wv * penalty_interval_slope(iv.v, -L.velocity.max_vel_x_backwards_mps, L.velocity.max_vel_x_mps, eps);
  if (sv != 0.0) {
    for (int j = 0; j < 7; ++j) J[14 + j] = sv * iv.dv[static_cast<std::size_t>(j)];
  }
  const double ww = std::sqrt(c.w->vel_th);
  r[3] = ww * penalty_symmetric(iv.w, L.velocity.max_vel_theta_radps, eps);
  const double sw = ww * penalty_symmetric_slope(iv.w, L.velocity.max_vel_theta_radps, eps);
  if (sw != 0.0) {
    for (int j = 0; j < 7; ++j) J[21 + j] = sw * iv.dw[static_cast<std::size_t>(j)];
  }
  // Time.
  const double wt = std::sqrt(c.w->time);
  r[4] = wt * time_error(dt);
  J[28 + 6] = wt;
}

void acc_jacobian(const TebResidualContext& c, const IntervalVelocity& iv1, const IntervalVelocity& iv2, double dt1,
                  double dt2, double* r, double* J) {
  const double eps = c.params->penalty_epsilon;
  for (int i = 0; i < 22; ++i) J[i] = 0.0;
  const double s = dt1 + dt2;
  const auto row = [&](double q1, double q2, const std::array<double, 7>& d1, const std::array<double, 7>& d2,
                       double weight, double bound, double* ri, double* Ji) {
    const double acc = acceleration(q1, q2, dt1, dt2);
    *ri = weight * penalty_symmetric(acc, bound, eps);
    const double slope = weight * penalty_symmetric_slope(acc, bound, eps);
    if (slope == 0.0) return;
    const double k = slope * 2.0 / s;
    // -d1 over (a, b, dt1), +d2 over (b, d, dt2), and -acc / s over both intervals.
    for (int j = 0; j < 6; ++j) Ji[j] -= k * d1[static_cast<std::size_t>(j)];
    for (int j = 0; j < 6; ++j) Ji[3 + j] += k * d2[static_cast<std::size_t>(j)];
    Ji[9] += -k * d1[6] - slope * acc / s;
    Ji[10] += k * d2[6] - slope * acc / s;
  };
  row(iv1.v, iv2.v, iv1.dv, iv2.dv, std::sqrt(c.w->acc_x), c.limits->velocity.acc_lim_x_mps2, &r[0], J);
  row(iv1.w, iv2.w, iv1.dw, iv2.dw, std::sqrt(c.w->acc_th), c.limits->velocity.acc_lim_theta_radps2, &r[1], J + 11);
}

void start_acc_jacobian(const TebResidualContext& c, const Twist& v0, const IntervalVelocity& iv, double dt, double* r,
                        double* J) {
  const double eps = c.params->penalty_epsilon;
  for (int i = 0; i < 14; ++i) J[i] = 0.0;
  const auto row = [&](double q, double q0, const std::array<double, 7>& dq, double weight, double bound, double* ri,
                       double* Ji) {
    const double acc = (q - q0) / dt;
    *ri = weight * penalty_symmetric(acc, bound, eps);
    const double slope = weight * penalty_symmetric_slope(acc, bound, eps);
    if (slope == 0.0) return;
    for (int j = 0; j < 7; ++j) Ji[j] = slope * dq[static_cast<std::size_t>(j)] / dt;
    Ji[6] -= slope * acc / dt;
  };
  row(iv.v, v0.linear_x, iv.dv, std::sqrt(c.w->acc_x), c.limits->velocity.acc_lim_x_mps2, &r[0], J);
  row(iv.w, v0.angular_z, iv.dw, std::sqrt(c.w->acc_th), c.limits->velocity.acc_lim_theta_radps2, &r[1], J + 7);
}

double dynamic_obstacle_jacobian(const TebResidualContext& c, const TebMovingObstacle& o, double t_s, double x,
                                 double y, double* J) {
  double g[2];
  const double d = o.lead_s > 0.0 ? segment_distance_gradient(x, y, o.at(t_s), o.lead_end(t_s), g)
                                  : point_distance_gradient(x, y, o.at(t_s), g);
  const double w = std::sqrt(c.w->dynamic_obstacle);
  const double bound = o.bound(t_s);
  const double active = d < bound + c.params->penalty_epsilon ? 1.0 : 0.0;
  J[0] = -w * g[0] * active;
  J[1] = -w * g[1] * active;
  return w * penalty_below(d, bound, c.params->penalty_epsilon);
}

double TebMovingObstacle::distance(const Eigen::Vector2d& p, double t_s) const {
  return lead_s > 0.0 ? distance_to_segment(p.x(), p.y(), at(t_s), lead_end(t_s)) : (p - at(t_s)).norm();
}

double obstacle_distance_gradient(const Obstacle& o, double x, double y, double* grad) {
  const auto& v = o.vertices;
  if (v.size() == 1) return point_distance_gradient(x, y, v[0], grad);
  if (v.size() == 2) return segment_distance_gradient(x, y, v[0], v[1], grad);
  bool inside = true;
  double g[2];
  double best = segment_distance_gradient(x, y, v.back(), v.front(), grad);
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Eigen::Vector2d& a = v[i];
    const Eigen::Vector2d& b = v[(i + 1) % v.size()];
    const double cross = (b.x() - a.x()) * (y - a.y()) - (b.y() - a.y()) * (x - a.x());
    if (cross < 0.0) inside = false;
    if (i + 1 < v.size()) {
      const double d = segment_distance_gradient(x, y, a, b, g);
      if (d < best) best = d, grad[0] = g[0], grad[1] = g[1];
    }
  }
  if (inside) {
    grad[0] = -grad[0];
    grad[1] = -grad[1];
    return -best;
  }
  return best;
}

}  // namespace bipednav::planning::local
