#pragma once

#include <Eigen/Core>
#include <vector>

#include "bipednav/common/se3.hpp"

namespace bipednav::localization {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

// Motion parameters x = [t; theta] (translation, rotation vector) of the LiDAR over one sweep,
// T^L_{k+1} in the reference. A point with time fraction s in [0, 1] is moved by the interpolated
// transform (eq. 4.8): rotation exp(s * theta^) (Rodrigues, eq. 4.9), then translation s * t
// (eq. 4.10).
Eigen::Vector3d apply_motion(const Vector6d& x, double s, const Eigen::Vector3d& p);
SE3 motion_to_se3(const Vector6d& x, double s = 1.0);
Vector6d se3_to_motion(const SE3& T);

// One row of eq. 4.13: a point-to-line (eq. 4.6) or point-to-plane (eq. 4.7) distance.
struct Constraint {
  Eigen::Vector3d point{0, 0, 0};   // the feature point before applying the motion
  double s = 1.0;                   // its time fraction within the sweep
  Eigen::Vector3d anchor{0, 0, 0};  // a point of the line or plane
  Eigen::Vector3d axis{0, 0, 1};    // unit line direction or unit plane normal
  bool is_line = false;
  double weight = 1.0;  // relative weight of the row (multiplies the bisquare weight)
};

// Distance of q to the constraint's line (>= 0) or signed distance to its plane.
double constraint_distance(const Constraint& c, const Eigen::Vector3d& q);
// Line through a and b (eq. 4.6 uses the two points of the edge correspondence).
Constraint line_constraint(const Eigen::Vector3d& point, double s, const Eigen::Vector3d& a, const Eigen::Vector3d& b);

// Tukey bisquare weight and loss with cut-off c (Algorithm 1, line 10).
double bisquare_weight(double r, double c);
double bisquare_loss(double r, double c);

// Weighted normal equations J^T W J, J^T W r accumulated row by row.
struct NormalEquations {
  Matrix6d H = Matrix6d::Zero();
  Vector6d g = Vector6d::Zero();
  double weight_sum = 0.0;
  std::size_t rows = 0;
  void add_row(const Eigen::Matrix<double, 1, 6>& J, double r, double w) {
    H.noalias() += w * J.transpose() * J;
    g.noalias() += w * J.transpose() * r;
    weight_sum += w;
    ++rows;
  }
};

// Degeneracy handling (after Zhang, Kaess and Singh, ICRA 2016, used by LOAM): eigen-directions of
// H / weight_sum with an eigenvalue below `min_eigenvalue` are not observable, so `delta` is
// projected onto the remaining directions. Returns the number of suppressed directions; their unit
// eigenvectors go to the first columns of `suppressed` when it is given.
int project_to_constrained(const Matrix6d& H, double weight_sum, double min_eigenvalue, Vector6d& delta,
                           Matrix6d* suppressed = nullptr);

// Solves (J^T W J + lambda diag(J^T W J)) delta = -J^T W d (eq. 4.14), with degenerate directions
// removed (their eigenvectors in the first `degenerate_dims` columns of `suppressed`, when given).
// Returns false when the system is singular or the step is not finite.
bool lm_step(const NormalEquations& ne, double lambda, double min_eigenvalue, Vector6d& delta, int& degenerate_dims,
             Matrix6d* suppressed = nullptr);

// The horizontal directions (x, y of the translation) among `count` suppressed directions (the
// first columns of `suppressed`, x = [t; theta]): the projector onto the span of their horizontal
// parts, keeping only parts at least half of a unit direction long (a direction that is mostly
// rotation or height leaves x and y observed). Zero when x and y are both observed.
Eigen::Matrix2d horizontal_weak_projector(const Matrix6d& suppressed, int count);

struct LmParams {
  int max_iterations = 8;
  double bisquare_c_m = 0.3;                // residuals beyond this get zero weight
  double initial_lambda = 1e-3;             // Levenberg-Marquardt damping
  double degenerate_min_eigenvalue = 0.02;  // of J^T W J per unit weight
  double converged_translation_m = 1e-4;
  double converged_rotation_rad = 1e-5;
  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v("max_iterations", max_iterations);
    v("bisquare_c_m", bisquare_c_m);
    v("initial_lambda", initial_lambda);
    v("degenerate_min_eigenvalue", degenerate_min_eigenvalue);
    v("converged_translation_m", converged_translation_m);
    v("converged_rotation_rad", converged_rotation_rad);
  }
};

struct LmSolution {
  Vector6d x = Vector6d::Zero();
  int iterations = 0;
  bool converged = false;
  int degenerate_dims = 0;  // directions left at the initial guess
  // Their unit eigenvectors (of J^T W J at the last step), in the first degenerate_dims columns.
  Matrix6d degenerate_directions = Matrix6d::Zero();
  std::size_t inliers = 0;  // rows with non-zero bisquare weight at the solution
  double rms_m = 0.0;       // RMS distance of the inliers
};

// Extra residual rows r = A x + b, weighted by `weight` each (in units of one full-weight point
// row), for a measurement of the motion itself (e.g. the tilt an IMU reports). Empty: none.
struct LinearPrior {
  Eigen::Matrix<double, Eigen::Dynamic, 6> A;
  Eigen::VectorXd b;
  double weight = 0.0;
  bool empty() const { return A.rows() == 0 || weight <= 0.0; }
};

// Levenberg-Marquardt on the stacked distances of fixed constraints (eq. 4.13-4.14), starting
// from x0; bisquare weights are recomputed every iteration. The prior's rows join the normal
// equations and the loss (they also count in the degeneracy test: a direction the prior fixes
// is not degenerate).
LmSolution solve_lm(const std::vector<Constraint>& constraints, const Vector6d& x0, const LmParams& p,
                    const LinearPrior& prior = {});

}  // namespace bipednav::localization
