#pragma once

// The numeric terms of the Timed-Elastic-Band objective (thesis section 5.2). Every term is a free
// function templated on the scalar so that the same code runs on doubles (tests, diagnostics) and
// on ceres::Jet (automatic Jacobians in the optimiser).

#include <Eigen/Core>
#include <cmath>
#include <type_traits>
#include <vector>

namespace bipednav::planning::local {

// Euclidean norm with a tiny floor so the derivative stays finite at zero length.
template <typename T>
T safe_norm(const T& dx, const T& dy) {
  using std::sqrt;
  return sqrt(dx * dx + dy * dy + T(1e-12));
}

// Angle wrapped to (-pi, pi]; shifting by whole turns keeps the derivative (1) exact for Jets and is
// much cheaper than atan2(sin, cos).
template <typename T>
T wrap_angle(T a) {
  constexpr double kTwoPi = 6.283185307179586;
  for (int i = 0; i < 64 && a > T(0.5 * kTwoPi); ++i) a -= T(kTwoPi);
  for (int i = 0; i < 64 && a <= T(-0.5 * kTwoPi); ++i) a += T(kTwoPi);
  return a;
}

// A heading's cosine and sine, for terms that share them: the terms below take them computed once (the
// same values, bit for bit, as each term computing its own; on Jets each is a sincos and a scaled vector).
template <typename T>
struct Heading {
  T c, s;
};
template <typename T>
Heading<T> heading(const T& th) {
  using std::cos;
  using std::sin;
  return {cos(th), sin(th)};
}

// eq. 5.6-5.7: h_k = (q_k + q_{k+1}) x d_{k,k+1} (z component); zero when both poses lie on a
// common arc of constant curvature (eq. 5.5). dx = x2 - x1, dy = y2 - y1.
template <typename T>
T nonholonomic_error(const Heading<T>& h1, const Heading<T>& h2, const T& dx, const T& dy) {
  return (h1.c + h2.c) * dy - (h1.s + h2.s) * dx;
}
template <typename T>
T nonholonomic_error(const T& x1, const T& y1, const T& th1, const T& x2, const T& y2, const T& th2) {
  const T dx = x2 - x1;
  const T dy = y2 - y1;
  return nonholonomic_error(heading(th1), heading(th2), dx, dy);
}

// eq. 5.10: smooth sign gamma*a / (1 + |gamma*a|) in [-1, 1].
template <typename T>
T smooth_sign(const T& a, double gain) {
  using std::abs;
  const T g = T(gain) * a;
  return g / (T(1.0) + abs(g));
}

// eq. 5.8: signed linear velocity between poses k and k+1 (sign from the heading h1 of pose k; dx = x2 - x1,
// dy = y2 - y1).
template <typename T>
T linear_velocity(const Heading<T>& h1, const T& dx, const T& dy, const T& dt, double sign_gain) {
  const T forward = h1.c * dx + h1.s * dy;  // <q_k, d_k,k+1>
  return safe_norm(dx, dy) / dt * smooth_sign(forward, sign_gain);
}
template <typename T>
T linear_velocity(const T& x1, const T& y1, const T& th1, const T& x2, const T& y2, const T& dt, double sign_gain) {
  const T dx = x2 - x1;
  const T dy = y2 - y1;
  return linear_velocity(heading(th1), dx, dy, dt, sign_gain);
}

// eq. 5.9: angular velocity between poses k and k+1.
template <typename T>
T angular_velocity(const T& th1, const T& th2, const T& dt) {
  return wrap_angle(T(th2 - th1)) / dt;
}

// eq. 5.11-5.12: acceleration from two consecutive velocities and their intervals.
template <typename T>
T acceleration(const T& v1, const T& v2, const T& dt1, const T& dt2) {
  return T(2.0) * (v2 - v1) / (dt1 + dt2);
}

// eq. 5.17-5.18 with an epsilon margin: how far `v` lies outside [lower + eps, upper - eps]
// (0 inside). The quadratic penalty is weight * this^2.
template <typename T>
T penalty_interval(const T& v, double lower, double upper, double eps) {
  if (v < T(lower + eps)) return T(lower + eps) - v;
  if (v > T(upper - eps)) return v - T(upper - eps);
  return T(0.0);
}

// Symmetric bound |v| <= bound (eq. 5.13, 5.14): max{0, |v| - (bound - eps)}.
template <typename T>
T penalty_symmetric(const T& v, double bound, double eps) {
  return penalty_interval(v, -bound, bound, eps);
}

// eq. 5.19 with margin: max{0, (bound + eps) - v}, the violation of v >= bound.
template <typename T>
T penalty_below(const T& v, double bound, double eps) {
  return v < T(bound + eps) ? T(bound + eps) - v : T(0.0);
}

// Backwards-walking penalty: positive when pose k+1 lies behind pose k's heading h1 (dx = x2 - x1, dy = y2 - y1).
template <typename T>
T backwards_error(const Heading<T>& h1, const T& dx, const T& dy) {
  return penalty_below(T(h1.c * dx + h1.s * dy), 0.0, 0.0);
}
template <typename T>
T backwards_error(const T& x1, const T& y1, const T& th1, const T& x2, const T& y2) {
  const T dx = x2 - x1;
  const T dy = y2 - y1;
  return backwards_error(heading(th1), dx, dy);
}

// Time optimality (eq. 5.4): the residual whose square is dT_k^2.
template <typename T>
T time_error(const T& dt) {
  return dt;
}

// Via-point attraction: residual vector whose squared norm is the squared distance.
template <typename T>
Eigen::Matrix<T, 2, 1> via_point_error(const T& x, const T& y, const Eigen::Vector2d& via) {
  return {x - T(via.x()), y - T(via.y())};
}

// Distance from (px, py) to a point obstacle.
template <typename T>
T distance_to_point(const T& px, const T& py, const Eigen::Vector2d& c) {
  return safe_norm(T(px - T(c.x())), T(py - T(c.y())));
}

// Distance from (px, py) to the segment a-b.
template <typename T>
T distance_to_segment(const T& px, const T& py, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  if (len2 < 1e-18) return distance_to_point(px, py, a);
  T t = ((px - T(a.x())) * T(ab.x()) + (py - T(a.y())) * T(ab.y())) / T(len2);
  if (t < T(0.0)) t = T(0.0);
  if (t > T(1.0)) t = T(1.0);
  return safe_norm(T(px - (T(a.x()) + t * T(ab.x()))), T(py - (T(a.y()) + t * T(ab.y()))));
}

// distance_to_segment's argument of the square root (doubles): the same arithmetic up to the root.
inline double squared_distance_to_segment(double px, double py, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  double dx = px - a.x(), dy = py - a.y();
  if (!(len2 < 1e-18)) {
    double t = ((px - a.x()) * ab.x() + (py - a.y()) * ab.y()) / len2;
    if (t < 0.0) t = 0.0;
    if (t > 1.0) t = 1.0;
    dx = px - (a.x() + t * ab.x());
    dy = py - (a.y() + t * ab.y());
  }
  return dx * dx + dy * dy + 1e-12;
}

// The scalar part of distance_to_point on ceres::Jet arguments (px, py the Jets' scalar parts), bitwise.
inline double jet_value_distance_to_point(double px, double py, const Eigen::Vector2d& c) {
  const double dx = px - c.x(), dy = py - c.y();
  return std::sqrt(dx * dx + dy * dy + 1e-12);
}

// The scalar part of distance_to_segment on ceres::Jet arguments (px, py the Jets' scalar parts), bitwise: a
// Jet's scalar part follows the double operations of its arithmetic, except that a Jet quotient multiplies by
// the divisor's reciprocal (so t is not the double version's quotient).
inline double jet_value_distance_to_segment(double px, double py, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  if (len2 < 1e-18) return jet_value_distance_to_point(px, py, a);
  double t = ((px - a.x()) * ab.x() + (py - a.y()) * ab.y()) * (1.0 / len2);
  if (t < 0.0) t = 0.0;
  if (t > 1.0) t = 1.0;
  const double dx = px - (a.x() + t * ab.x()), dy = py - (a.y() + t * ab.y());
  return std::sqrt(dx * dx + dy * dy + 1e-12);
}

// distance_to_polygon on Jets (>= 3 vertices), decided on the scalar parts: the edge whose Jet it
// returns (from v[edge] to v[(edge + 1) % size]: the first of the closing edge, then edges 0, 1, ... with
// the least distance, the edge a loop over every edge keeps), whether the point is inside, and the returned
// scalar part.
struct JetPolygonNearest {
  std::size_t edge = 0;
  bool inside = true;
  double value = 0.0;
};
inline JetPolygonNearest jet_polygon_nearest(double px, double py, const std::vector<Eigen::Vector2d>& v) {
  JetPolygonNearest out;
  out.edge = v.size() - 1;
  double best = jet_value_distance_to_segment(px, py, v.back(), v.front());
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Eigen::Vector2d& a = v[i];
    const Eigen::Vector2d& b = v[(i + 1) % v.size()];
    const double cross = (b.x() - a.x()) * (py - a.y()) - (b.y() - a.y()) * (px - a.x());
    if (cross < 0.0) out.inside = false;
    if (i + 1 < v.size()) {
      const double d = jet_value_distance_to_segment(px, py, a, b);
      if (d < best) best = d, out.edge = i;
    }
  }
  out.value = out.inside ? -best : best;
  return out;
}

// Signed distance from (px, py) to a convex polygon (vertices counter-clockwise): negative inside
// (minus the depth), so the gradient keeps pushing out of an obstacle. Bitwise the least of every edge's
// distance_to_segment in T (the reference in teb_residuals_test.cpp), with the work of one edge in T: for
// doubles one square root (the nearest edge's), for Jets the edges compared on their scalar parts
// (jet_polygon_nearest) and the derivatives of the nearest one only.
template <typename T>
T distance_to_polygon(const T& px, const T& py, const std::vector<Eigen::Vector2d>& v) {
  if (v.size() == 1) return distance_to_point(px, py, v[0]);
  if (v.size() == 2) return distance_to_segment(px, py, v[0], v[1]);
  if constexpr (std::is_same_v<T, double>) {
    // One square root for the nearest edge: the root is monotonic, so the root of the least square is the
    // least of the edges' distances (bitwise), as the generic code computes it.
    bool inside = true;
    double best = squared_distance_to_segment(px, py, v.back(), v.front());
    for (std::size_t i = 0; i < v.size(); ++i) {
      const Eigen::Vector2d& a = v[i];
      const Eigen::Vector2d& b = v[(i + 1) % v.size()];
      const double cross = (b.x() - a.x()) * (py - a.y()) - (b.y() - a.y()) * (px - a.x());
      if (cross < 0.0) inside = false;
      if (i + 1 < v.size()) {
        const double d = squared_distance_to_segment(px, py, a, b);
        if (d < best) best = d;
      }
    }
    const double d = std::sqrt(best);
    return inside ? -d : d;
  } else {
    const JetPolygonNearest n = jet_polygon_nearest(px.a, py.a, v);
    const T d = distance_to_segment(px, py, v[n.edge], v[(n.edge + 1) % v.size()]);
    return n.inside ? -d : d;
  }
}

// Double-precision conveniences of the terms above, for diagnostics and tests.
double nonholonomic_error(double x1, double y1, double th1, double x2, double y2, double th2);
// Exact signed velocity of the first interval (sign of the forward projection, no smoothing).
double exact_linear_velocity(double x1, double y1, double th1, double x2, double y2, double dt);

}  // namespace bipednav::planning::local
