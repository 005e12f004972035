#include "bipednav/localization/registration_lm.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "bipednav/common/error.hpp"

namespace bipednav::localization {

namespace {

Eigen::Matrix3d skew_matrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d K;
  K << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return K;
}

// exp(theta^) = I + a theta^ + b theta^2 (Rodrigues) with a = sin|theta| / |theta| and
// b = (1 - cos|theta|) / |theta|^2. Per-sweep rotations are small, where the series (truncation
// below 1e-13) replaces sin and cos: this runs once per point and constraint.
struct RodriguesCoefficients {
  double a = 1.0, b = 0.5;
  explicit RodriguesCoefficients(const Eigen::Vector3d& theta) {
    const double t2 = theta.squaredNorm();
    if (t2 < 0.0625) {  // |theta| < 0.25 rad
      a = 1.0 - t2 / 6.0 * (1.0 - t2 / 20.0 * (1.0 - t2 / 42.0 * (1.0 - t2 / 72.0)));
      b = 0.5 * (1.0 - t2 / 12.0 * (1.0 - t2 / 30.0 * (1.0 - t2 / 56.0 * (1.0 - t2 / 90.0))));
    } else {
      const double angle = std::sqrt(t2);
      a = std::sin(angle) / angle;
      b = (1.0 - std::cos(angle)) / t2;
    }
  }
};

Eigen::Matrix3d rodrigues(const Eigen::Vector3d& theta) {
  const RodriguesCoefficients c(theta);
  // theta^ theta^ = theta theta^T - |theta|^2 I
  Eigen::Matrix3d R = c.b * theta * theta.transpose() + c.a * skew_matrix(theta);
  R.diagonal().array() += 1.0 - c.b * theta.squaredNorm();
  return R;
}

// exp(theta^) p without forming the matrix, with theta's coefficients.
Eigen::Vector3d rotate(const RodriguesCoefficients& c, const Eigen::Vector3d& theta, const Eigen::Vector3d& p) {
  const Eigen::Vector3d tp = theta.cross(p);
  return p + c.a * tp + c.b * theta.cross(tp);
}

Eigen::Vector3d rotate(const Eigen::Vector3d& theta, const Eigen::Vector3d& p) {
  return rotate(RodriguesCoefficients(theta), theta, p);
}

// Derivative of the constraint distance with respect to the moved point.
Eigen::Vector3d distance_gradient(const Constraint& c, const Eigen::Vector3d& q) {
  if (!c.is_line) return c.axis;
  const Eigen::Vector3d v = q - c.anchor;
  const Eigen::Vector3d e = v - c.axis.dot(v) * c.axis;
  const double n = e.norm();
  return n > 1e-12 ? Eigen::Vector3d(e / n) : Eigen::Vector3d::Zero();
}

// The constraints' rows at one x: each point rotated (rp), moved (q = rp + s t) and its distance.
// solve_lm evaluates the loss at every candidate and linearizes at the accepted one: the rows are
// kept from the loss, not computed twice.
struct Rows {
  std::vector<Eigen::Vector3d> rp, q;
  std::vector<double> r;
};

// The robust loss at x; fills `rows`. The points of one constraint set often share their time
// fraction (all of them in the mapping step): the rotation's coefficients are computed once per run
// of equal fractions (the same values as computed per point).
double evaluate(const std::vector<Constraint>& cs, const Vector6d& x, double c, const LinearPrior& prior, Rows& rows) {
  rows.rp.resize(cs.size());
  rows.q.resize(cs.size());
  rows.r.resize(cs.size());
  double sum = 0.0;
  double last_s = 0.0;
  bool have_s = false;
  Eigen::Vector3d theta = Eigen::Vector3d::Zero();
  RodriguesCoefficients coefficients(theta);
  for (std::size_t i = 0; i < cs.size(); ++i) {
    const Constraint& k = cs[i];
    if (!have_s || !(k.s == last_s) || std::signbit(k.s) != std::signbit(last_s)) {
      theta = k.s * x.tail<3>();
      coefficients = RodriguesCoefficients(theta);
      last_s = k.s;
      have_s = true;
    }
    const Eigen::Vector3d rp = rotate(coefficients, theta, k.point);
    const Eigen::Vector3d q = rp + k.s * x.head<3>();
    const double r = constraint_distance(k, q);
    rows.rp[i] = rp;
    rows.q[i] = q;
    rows.r[i] = r;
    sum += k.weight * bisquare_loss(r, c);
  }
  if (!prior.empty()) sum += 0.5 * prior.weight * (prior.A * x + prior.b).squaredNorm();
  return sum;
}

// The normal equations at the x `rows` were evaluated at.
NormalEquations linearize(const std::vector<Constraint>& cs, const Rows& rows, const Vector6d& x, double c,
                          const LinearPrior& prior) {
  NormalEquations ne;
  if (!prior.empty()) {
    const Eigen::VectorXd r = prior.A * x + prior.b;
    ne.H.noalias() += prior.weight * prior.A.transpose() * prior.A;
    ne.g.noalias() += prior.weight * prior.A.transpose() * r;
  }
  for (std::size_t i = 0; i < cs.size(); ++i) {
    const Constraint& k = cs[i];
    const double r = rows.r[i];
    const double w = k.weight * bisquare_weight(r, c);
    if (w <= 0.0) continue;
    const Eigen::Vector3d& rp = rows.rp[i];
    const Eigen::Vector3d grad = distance_gradient(k, rows.q[i]);
    Eigen::Matrix<double, 1, 6> J;
    // dq/dt = s I; dq/dtheta ~= -s [R p]x (first-order rotation perturbation).
    J.head<3>() = k.s * grad.transpose();
    J.tail<3>() = k.s * rp.cross(grad).transpose();
    ne.add_row(J, r, w);
  }
  return ne;
}

}  // namespace

Eigen::Vector3d apply_motion(const Vector6d& x, double s, const Eigen::Vector3d& p) {
  return rotate(s * x.tail<3>(), p) + s * x.head<3>();
}

SE3 motion_to_se3(const Vector6d& x, double s) {
  SE3 T = SE3::Identity();
  T.linear() = rodrigues(s * x.tail<3>());
  T.translation() = s * x.head<3>();
  return T;
}

Vector6d se3_to_motion(const SE3& T) {
  Vector6d x;
  const Eigen::AngleAxisd aa(T.rotation());
  x.head<3>() = T.translation();
  x.tail<3>() = aa.angle() * aa.axis();
  return x;
}

double constraint_distance(const Constraint& c, const Eigen::Vector3d& q) {
  const Eigen::Vector3d v = q - c.anchor;
  if (!c.is_line) return c.axis.dot(v);
  return (v - c.axis.dot(v) * c.axis).norm();
}

Constraint line_constraint(const Eigen::Vector3d& point, double s, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  Constraint c;
  c.point = point;
  c.s = s;
  c.anchor = a;
  const Eigen::Vector3d d = b - a;
  c.axis = d.norm() > 1e-9 ? Eigen::Vector3d(d.normalized()) : Eigen::Vector3d::UnitZ();
  c.is_line = true;
  return c;
}

double bisquare_weight(double r, double c) {
  const double u = r / c;
  if (std::abs(u) >= 1.0) return 0.0;
  const double v = 1.0 - u * u;
  return v * v;
}

double bisquare_loss(double r, double c) {
  const double u = r / c;
  if (std::abs(u) >= 1.0) return c * c / 6.0;
  const double v = 1.0 - u * u;
  return c * c / 6.0 * (1.0 - v * v * v);
}

int project_to_constrained(const Matrix6d& H, double weight_sum, double min_eigenvalue, Vector6d& delta,
                           Matrix6d* suppressed) {
  if (weight_sum <= 0.0) {
    delta.setZero();
    if (suppressed) suppressed->setIdentity();
    return 6;
  }
  const Eigen::SelfAdjointEigenSolver<Matrix6d> es(H / weight_sum);
  int count = 0;
  Vector6d projected = Vector6d::Zero();
  for (int i = 0; i < 6; ++i) {
    const Vector6d v = es.eigenvectors().col(i);
    if (es.eigenvalues()(i) < min_eigenvalue) {
      if (suppressed) suppressed->col(count) = v;
      ++count;
      continue;
    }
    projected += v * v.dot(delta);
  }
  delta = projected;
  return count;
}

Eigen::Matrix2d horizontal_weak_projector(const Matrix6d& suppressed, int count) {
  Eigen::Matrix2d M = Eigen::Matrix2d::Zero();
  for (int i = 0; i < std::min(count, 6); ++i) {
    const Eigen::Vector2d h = suppressed.col(i).head<2>();
    M += h * h.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(M);
  Eigen::Matrix2d P = Eigen::Matrix2d::Zero();
  for (int i = 0; i < 2; ++i) {
    if (es.eigenvalues()(i) < 0.25) continue;  // a horizontal part shorter than half a unit
    const Eigen::Vector2d u = es.eigenvectors().col(i);
    P += u * u.transpose();
  }
  return P;
}

bool lm_step(const NormalEquations& ne, double lambda, double min_eigenvalue, Vector6d& delta, int& degenerate_dims,
             Matrix6d* suppressed) {
  Matrix6d A = ne.H;
  A.diagonal() += lambda * ne.H.diagonal() + Vector6d::Constant(1e-9);
  delta = -A.ldlt().solve(ne.g);
  if (!delta.allFinite()) return false;
  degenerate_dims = project_to_constrained(ne.H, ne.weight_sum, min_eigenvalue, delta, suppressed);
  return delta.allFinite();
}

void LmParams::validate() const {
  require(max_iterations >= 1, "max_iterations", ">= 1");
  require(bisquare_c_m > 0.0, "bisquare_c_m", "> 0");
  require(initial_lambda >= 0.0, "initial_lambda", ">= 0");
  require(degenerate_min_eigenvalue >= 0.0, "degenerate_min_eigenvalue", ">= 0");
  require(converged_translation_m > 0.0, "converged_translation_m", "> 0");
  require(converged_rotation_rad > 0.0, "converged_rotation_rad", "> 0");
}

LmSolution solve_lm(const std::vector<Constraint>& constraints, const Vector6d& x0, const LmParams& p,
                    const LinearPrior& prior) {
  LmSolution sol;
  sol.x = x0;
  double lambda = p.initial_lambda;
  Rows rows, candidate_rows;  // at sol.x and at the candidate
  double loss = evaluate(constraints, sol.x, p.bisquare_c_m, prior, rows);
  NormalEquations ne;
  bool linearized = false;  // ne is at sol.x (a rejected step leaves x, and so ne, as they were)
  for (sol.iterations = 0; sol.iterations < p.max_iterations;) {
    if (!linearized) ne = linearize(constraints, rows, sol.x, p.bisquare_c_m, prior);
    linearized = true;
    ++sol.iterations;
    Vector6d delta;
    if (ne.rows < 6 ||
        !lm_step(ne, lambda, p.degenerate_min_eigenvalue, delta, sol.degenerate_dims, &sol.degenerate_directions)) {
      sol.degenerate_dims = 6;
      sol.degenerate_directions.setIdentity();
      break;
    }
    const Vector6d candidate = sol.x + delta;
    const double candidate_loss = evaluate(constraints, candidate, p.bisquare_c_m, prior, candidate_rows);
    if (candidate_loss <= loss) {
      sol.x = candidate;
      loss = candidate_loss;
      std::swap(rows, candidate_rows);
      linearized = false;
      lambda = std::max(lambda * 0.1, 1e-7);
      if (delta.head<3>().norm() < p.converged_translation_m && delta.tail<3>().norm() < p.converged_rotation_rad) {
        sol.converged = true;
        break;
      }
    } else {
      lambda = lambda > 0.0 ? lambda * 10.0 : 1e-4;
      if (lambda > 1e4) {
        sol.converged = true;  // no descent direction left: at a (local) minimum
        break;
      }
    }
  }
  double sq = 0.0;
  for (const double r : rows.r) {  // the distances at sol.x
    if (std::abs(r) < p.bisquare_c_m) {
      ++sol.inliers;
      sq += r * r;
    }
  }
  sol.rms_m = sol.inliers > 0 ? std::sqrt(sq / static_cast<double>(sol.inliers)) : 0.0;
  return sol;
}

}  // namespace bipednav::localization
