#pragma once

// A Levenberg-Marquardt solver dedicated to the timed elastic band: analytic Jacobians (teb_residuals) and
// the normal equations in block-band form. The free variables are ordered dT_0, s_1, dT_1, s_2, ..., s_{n-2},
// dT_{n-2} (the first and last pose are fixed), so every residual block touches at most 11 consecutive
// variables and J^T J is a band matrix of half-bandwidth 10: one solve costs O(n), not a sparse
// factorisation. The trust-region logic follows Ceres' LEVENBERG_MARQUARDT strategy with its default
// options (Jacobi scaling, radius update, projected Armijo line search for the dT lower bounds, function
// and parameter tolerances), so the result matches the Ceres solve of the same problem up to rounding.

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "bipednav/common/twist.hpp"
#include "bipednav/planning/local/costmap_obstacles.hpp"
#include "bipednav/planning/local/teb_residuals.hpp"

namespace bipednav::planning::local {

// One solve's problem besides the band's variables.
struct TebLmProblem {
  TebResidualContext ctx{};
  const std::vector<Obstacle>* obstacles = nullptr;      // may be null
  const std::vector<std::vector<int>>* assoc = nullptr;  // per pose: indices into obstacles (may be null)
  const std::vector<std::pair<std::size_t, Eigen::Vector2d>>* via = nullptr;  // (pose index, via point)
  // Moving obstacles against every inner pose, pose k at pose_times[k] (both null or both set).
  const std::vector<TebMovingObstacle>* moving = nullptr;
  const std::vector<double>* pose_times = nullptr;
  Twist start_velocity;
  double dt_min_s = 0.01;
  int max_iterations = 5;
  double function_tolerance = 1e-4;
};

struct TebLmSummary {
  double initial_cost = 0.0;  // 1/2 sum r^2, as Ceres reports it
  double final_cost = 0.0;
  int iterations = 0;
  int successful_steps = 0;
  bool converged = false;  // a tolerance ended the solve (else the iteration limit)
};

class TebLmSolver {
 public:
  // Optimises x (3 per pose; the first and last pose stay fixed) and dt (dt.size() + 1 poses, each
  // dT >= dt_min_s) in place. Returns false when the problem cannot be evaluated (non-finite cost) or the
  // linear solves keep failing; x and dt then hold the last accepted iterate.
  bool solve(const TebLmProblem& problem, std::vector<double>& x, std::vector<double>& dt,
             TebLmSummary* summary = nullptr);

  // 1/2 sum r^2 of the problem at (x, dt), its gradient with respect to the free variables in the order
  // above and J^T J as a dense matrix (for tests).
  double evaluate_dense(const TebLmProblem& problem, const std::vector<double>& x, const std::vector<double>& dt,
                        Eigen::VectorXd* gradient, Eigen::MatrixXd* jtj);

  static constexpr int kHalfBandwidth = 10;

 private:
  enum class Mode { kCost, kGradient, kFull };
  double evaluate(const std::vector<double>& z, Mode mode, std::vector<double>& grad, std::vector<double>& hband);
  static void add_block(int m, int cols, const double* r, const double* J, const int* idx, Mode mode,
                        std::vector<double>& grad, std::vector<double>& hband, double& cost);
  void bind(const TebLmProblem& problem, const std::vector<double>& x, const std::vector<double>& dt);
  void unbind(std::vector<double>& x, std::vector<double>& dt) const;
  void project(std::vector<double>& z) const;
  const double* pose(const std::vector<double>& z, std::size_t k) const;
  int pose_index(std::size_t k) const;
  // Returns the step length; *first_accepted: the full step satisfied the Armijo condition at once, and
  // its cost, gradient and J^T J are in (*first_cost, grad_trial_, htrial_).
  double line_search(const std::vector<double>& z, double cost, const std::vector<double>& grad,
                     const std::vector<double>& delta, bool* first_accepted, double* first_cost);

  const TebLmProblem* p_ = nullptr;
  std::size_t n_ = 0;   // poses
  std::size_t nz_ = 0;  // free variables
  double first_[3]{}, last_[3]{};
  std::vector<double> z_, cand_, trial_, delta_, step_, grad_, grad_trial_, scale_, hband_, htrial_, aband_;
  std::vector<double> cos_, sin_;  // of each pose's heading
  std::vector<std::size_t> envelope_;
  std::vector<IntervalVelocity> iv_;
};

}  // namespace bipednav::planning::local
