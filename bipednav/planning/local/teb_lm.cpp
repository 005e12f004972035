#include "bipednav/planning/local/teb_lm.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bipednav/planning/local/band_cholesky.hpp"
#include "bipednav/planning/local/interpolated_step.hpp"

namespace bipednav::planning::local {

namespace {

constexpr int kB = TebLmSolver::kHalfBandwidth;
constexpr int kW = kB + 1;  // stored entries per row of the lower band (band_cholesky.hpp)

// Ceres' defaults (Solver::Options) for the trust region and the projected line search.
constexpr double kInitialRadius = 1e4;
constexpr double kMaxRadius = 1e16;
constexpr double kMinRadius = 1e-32;
constexpr double kMinDiagonal = 1e-6;
constexpr double kMaxDiagonal = 1e32;
constexpr double kMinRelativeDecrease = 1e-3;
constexpr double kGradientTolerance = 1e-10;
constexpr double kParameterTolerance = 1e-8;
constexpr int kMaxConsecutiveInvalidSteps = 5;
constexpr double kSufficientDecrease = 1e-4;
constexpr double kMaxStepContraction = 1e-3;
constexpr double kMinStepContraction = 0.6;
constexpr double kMinLineSearchStep = 1e-9;
constexpr int kMaxLineSearchIterations = 20;

}  // namespace

const double* TebLmSolver::pose(const std::vector<double>& z, std::size_t k) const {
  if (k == 0) return first_;
  if (k + 1 == n_) return last_;
  return &z[4 * k - 3];
}

int TebLmSolver::pose_index(std::size_t k) const { return (k == 0 || k + 1 == n_) ? -1 : static_cast<int>(4 * k - 3); }

void TebLmSolver::bind(const TebLmProblem& problem, const std::vector<double>& x, const std::vector<double>& dt) {
  p_ = &problem;
  n_ = dt.size() + 1;
  nz_ = 4 * n_ - 7;
  for (int c = 0; c < 3; ++c) first_[c] = x[static_cast<std::size_t>(c)], last_[c] = x[3 * (n_ - 1) + c];
  z_.assign(nz_, 0.0);
  for (std::size_t k = 0; k + 1 < n_; ++k) {
    z_[4 * k] = dt[k];
    if (k > 0) {
      for (int c = 0; c < 3; ++c) z_[4 * k - 3 + c] = x[3 * k + c];
    }
  }
  iv_.resize(n_ - 1);
}

void TebLmSolver::unbind(std::vector<double>& x, std::vector<double>& dt) const {
  for (std::size_t k = 0; k + 1 < n_; ++k) {
    dt[k] = z_[4 * k];
    if (k > 0) {
      for (int c = 0; c < 3; ++c) x[3 * k + c] = z_[4 * k - 3 + c];
    }
  }
}

void TebLmSolver::project(std::vector<double>& z) const {
  for (std::size_t k = 0; k + 1 < n_; ++k) z[4 * k] = std::max(z[4 * k], p_->dt_min_s);
}

void TebLmSolver::add_block(int m, int cols, const double* r, const double* J, const int* idx, Mode mode,
                            std::vector<double>& grad, std::vector<double>& hband, double& cost) {
  int nzi[11];
  double nzv[11];
  for (int i = 0; i < m; ++i) {
    cost += 0.5 * r[i] * r[i];
    if (mode == Mode::kCost) continue;
    int cnt = 0;
    for (int j = 0; j < cols; ++j) {
      const double v = J[i * cols + j];
      if (v == 0.0 || idx[j] < 0) continue;
      nzi[cnt] = idx[j], nzv[cnt] = v, ++cnt;
      grad[static_cast<std::size_t>(idx[j])] += v * r[i];
    }
    if (mode != Mode::kFull) continue;
    for (int a = 0; a < cnt; ++a) {
      for (int b = 0; b <= a; ++b) {
        const int hi = std::max(nzi[a], nzi[b]), lo = std::min(nzi[a], nzi[b]);
        hband[static_cast<std::size_t>(hi) * kW + static_cast<std::size_t>(hi - lo)] += nzv[a] * nzv[b];
      }
    }
  }
}

double TebLmSolver::evaluate(const std::vector<double>& z, Mode mode, std::vector<double>& grad,
                             std::vector<double>& hband) {
  const TebResidualContext& c = p_->ctx;
  double cost = 0.0;
  if (mode != Mode::kCost) grad.assign(nz_, 0.0);
  if (mode == Mode::kFull) hband.assign(nz_ * kW, 0.0);
  const double gain = c.params->sign_gain;
  cos_.resize(n_), sin_.resize(n_);
  for (std::size_t k = 0; k < n_; ++k) {
    const double th = pose(z, k)[2];
    cos_[k] = std::cos(th), sin_[k] = std::sin(th);
  }
  for (std::size_t k = 0; k + 1 < n_; ++k)
    iv_[k] = interval_velocity(pose(z, k), pose(z, k + 1), z[4 * k], gain, cos_[k], sin_[k]);
  double r[5], J[35];
  int idx[11];
  const auto set_pose = [&](int* out, std::size_t k) {
    const int b = pose_index(k);
    for (int i = 0; i < 3; ++i) out[i] = b < 0 ? -1 : b + i;
  };
  for (std::size_t k = 0; k + 1 < n_; ++k) {
    set_pose(idx, k);
    set_pose(idx + 3, k + 1);
    idx[6] = static_cast<int>(4 * k);
    edge_jacobian(c, pose(z, k), pose(z, k + 1), z[4 * k], iv_[k], cos_[k], sin_[k], cos_[k + 1], sin_[k + 1], r, J);
    add_block(5, 7, r, J, idx, mode, grad, hband, cost);
    if (k == 0) {
      start_acc_jacobian(c, p_->start_velocity, iv_[0], z[0], r, J);
      add_block(2, 7, r, J, idx, mode, grad, hband, cost);
    }
  }
  double Ja[22];
  for (std::size_t k = 0; k + 2 < n_; ++k) {
    set_pose(idx, k);
    set_pose(idx + 3, k + 1);
    set_pose(idx + 6, k + 2);
    idx[9] = static_cast<int>(4 * k);
    idx[10] = static_cast<int>(4 * k + 4);
    acc_jacobian(c, iv_[k], iv_[k + 1], z[4 * k], z[4 * k + 4], r, Ja);
    add_block(2, 11, r, Ja, idx, mode, grad, hband, cost);
  }
  const int kobs = c.params->obstacles_per_pose;
  if (p_->obstacles != nullptr && p_->assoc != nullptr && kobs > 0) {
    const double wo = std::sqrt(c.w->obstacle);
    const double bound = c.limits->min_obstacle_dist_m + c.params->penalty_epsilon;
    for (std::size_t k = 1; k + 1 < n_ && k < p_->assoc->size(); ++k) {
      const auto& as = (*p_->assoc)[k];
      const double* q = pose(z, k);
      idx[0] = pose_index(k), idx[1] = idx[0] < 0 ? -1 : idx[0] + 1;
      for (std::size_t i = 0; i < as.size() && static_cast<int>(i) < kobs; ++i) {
        double g[2];
        const double d = obstacle_distance_gradient((*p_->obstacles)[static_cast<std::size_t>(as[i])], q[0], q[1], g);
        r[0] = wo * penalty_below(d, c.limits->min_obstacle_dist_m, c.params->penalty_epsilon);
        J[0] = d < bound ? -wo * g[0] : 0.0;
        J[1] = d < bound ? -wo * g[1] : 0.0;
        add_block(1, 2, r, J, idx, mode, grad, hband, cost);
      }
    }
  }
  if (p_->moving != nullptr && p_->pose_times != nullptr) {
    for (std::size_t k = 1; k + 1 < n_ && k < p_->pose_times->size(); ++k) {
      const double* q = pose(z, k);
      idx[0] = pose_index(k), idx[1] = idx[0] < 0 ? -1 : idx[0] + 1;
      for (const auto& o : *p_->moving) {
        r[0] = dynamic_obstacle_jacobian(c, o, (*p_->pose_times)[k], q[0], q[1], J);
        add_block(1, 2, r, J, idx, mode, grad, hband, cost);
      }
    }
  }
  if (p_->via != nullptr) {
    const double wv = std::sqrt(c.w->via);
    for (const auto& [k, v] : *p_->via) {
      if (k >= n_) continue;
      const double* q = pose(z, k);
      via_residuals(c, v, q, r);
      J[0] = wv, J[1] = 0.0, J[2] = 0.0, J[3] = wv;
      idx[0] = pose_index(k), idx[1] = idx[0] < 0 ? -1 : idx[0] + 1;
      add_block(2, 2, r, J, idx, mode, grad, hband, cost);
    }
  }
  return cost;
}

double TebLmSolver::evaluate_dense(const TebLmProblem& problem, const std::vector<double>& x,
                                   const std::vector<double>& dt, Eigen::VectorXd* gradient, Eigen::MatrixXd* jtj) {
  bind(problem, x, dt);
  const double cost = evaluate(z_, Mode::kFull, grad_, hband_);
  if (gradient != nullptr) *gradient = Eigen::Map<const Eigen::VectorXd>(grad_.data(), static_cast<Eigen::Index>(nz_));
  if (jtj != nullptr) {
    const auto n = static_cast<Eigen::Index>(nz_);
    jtj->setZero(n, n);
    for (Eigen::Index i = 0; i < n; ++i) {
      for (Eigen::Index d = 0; d < kW && d <= i; ++d) {
        const double v = hband_[static_cast<std::size_t>(i * kW + d)];
        (*jtj)(i, i - d) = v;
        (*jtj)(i - d, i) = v;
      }
    }
  }
  return cost;
}

// Ceres' projected Armijo line search along delta from z (TrustRegionMinimizer::DoLineSearch): returns
// the step length to scale delta by (1 when the full step decreases the cost enough or the search fails).
double TebLmSolver::line_search(const std::vector<double>& z, double cost, const std::vector<double>& grad,
                                const std::vector<double>& delta, bool* first_accepted, double* first_cost) {
  double g0 = 0.0, dmax = 0.0;
  for (std::size_t i = 0; i < nz_; ++i) g0 += grad[i] * delta[i], dmax = std::max(dmax, std::abs(delta[i]));
  const auto sample = [&](double a, Mode mode) {
    LineSearchSample s;
    s.x = a;
    for (std::size_t i = 0; i < nz_; ++i) trial_[i] = z[i] + a * delta[i];
    project(trial_);
    s.value = evaluate(trial_, mode, grad_trial_, htrial_);
    double slope = 0.0;
    for (std::size_t i = 0; i < nz_; ++i) slope += delta[i] * grad_trial_[i];
    s.slope = slope;
    s.valid = std::isfinite(s.value) && std::isfinite(s.slope);
    return s;
  };
  const LineSearchSample s0{0.0, cost, g0, true};
  LineSearchSample prev;
  // The full step is usually accepted: evaluate J^T J there too, so an accepted step needs no further
  // evaluation.
  LineSearchSample cur = sample(1.0, Mode::kFull);
  *first_accepted = cur.valid && !(cur.value > cost + kSufficientDecrease * g0 * cur.x);
  *first_cost = cur.value;
  int iterations = 0;
  while (!cur.valid || cur.value > cost + kSufficientDecrease * g0 * cur.x) {
    if (++iterations >= kMaxLineSearchIterations) return 1.0;
    const double a = interpolated_step(s0, prev, cur, kMaxStepContraction * cur.x, kMinStepContraction * cur.x);
    if (a * dmax < kMinLineSearchStep) return 1.0;
    prev = cur;
    cur = sample(a, Mode::kGradient);
  }
  return cur.x;
}

bool TebLmSolver::solve(const TebLmProblem& problem, std::vector<double>& x, std::vector<double>& dt,
                        TebLmSummary* summary) {
  TebLmSummary sum;
  if (dt.empty() || x.size() != 3 * (dt.size() + 1)) return false;
  bind(problem, x, dt);
  project(z_);
  cand_.resize(nz_), trial_.resize(nz_), delta_.resize(nz_), step_.resize(nz_), scale_.resize(nz_);
  aband_.resize(nz_ * kW);
  const auto norm = [&](const std::vector<double>& v) {
    double s = 0.0;
    for (std::size_t i = 0; i < nz_; ++i) s += v[i] * v[i];
    return std::sqrt(s);
  };
  const auto projected_gradient_max_norm = [&]() {
    double m = 0.0;
    for (std::size_t i = 0; i < nz_; ++i) {
      double y = z_[i] - grad_[i];
      if (i % 4 == 0) y = std::max(y, p_->dt_min_s);
      m = std::max(m, std::abs(z_[i] - y));
    }
    return m;
  };
  double x_norm = norm(z_);
  double cost = evaluate(z_, Mode::kFull, grad_, hband_);
  sum.initial_cost = sum.final_cost = cost;
  if (!std::isfinite(cost)) {
    if (summary != nullptr) *summary = sum;
    return false;
  }
  // Jacobi scaling from the first Jacobian's column norms, kept for the whole solve.
  for (std::size_t i = 0; i < nz_; ++i) scale_[i] = 1.0 / (1.0 + std::sqrt(hband_[i * kW]));
  double gmax = projected_gradient_max_norm();
  double radius = kInitialRadius, decrease = 2.0;
  bool successful = true;
  int invalid = 0;
  bool ok = true;
  int iteration = 0;
  while (true) {
    if (iteration >= p_->max_iterations) break;
    if (successful && gmax <= kGradientTolerance) {
      sum.converged = true;
      break;
    }
    if (radius <= kMinRadius) {
      sum.converged = true;
      break;
    }
    ++iteration;
    // (S H S + diag(S H S) / radius) y = S g, step = -y (scaled variables).
    for (std::size_t i = 0; i < nz_; ++i) {
      const std::size_t d1 = std::min<std::size_t>(kB, i);
      for (std::size_t d = 0; d <= d1; ++d) aband_[i * kW + d] = scale_[i] * hband_[i * kW + d] * scale_[i - d];
      const double diag = std::clamp(aband_[i * kW], kMinDiagonal, kMaxDiagonal);
      aband_[i * kW] += diag / radius;
      step_[i] = scale_[i] * grad_[i];
    }
    bool valid = band_cholesky<kB>(aband_, nz_, envelope_);
    double model_change = 0.0;
    if (valid) {
      band_solve<kB>(aband_, nz_, step_);
      for (std::size_t i = 0; i < nz_; ++i) step_[i] = -step_[i];
      // model_change = -(s' S g + 1/2 s' S H S s)
      double lin = 0.0, quad = 0.0;
      for (std::size_t i = 0; i < nz_; ++i) {
        lin += step_[i] * scale_[i] * grad_[i];
        double hs = scale_[i] * hband_[i * kW] * scale_[i] * step_[i];
        const std::size_t d1 = std::min<std::size_t>(kB, i);
        for (std::size_t d = 1; d <= d1; ++d) {
          const double h = scale_[i] * hband_[i * kW + d] * scale_[i - d];
          hs += h * step_[i - d];
          quad += h * step_[i] * step_[i - d];  // the upper triangle's mirror entry
        }
        quad += step_[i] * hs;
      }
      model_change = -(lin + 0.5 * quad);
      valid = std::isfinite(model_change) && model_change > 0.0;
    }
    if (!valid) {
      if (++invalid >= kMaxConsecutiveInvalidSteps) {
        ok = false;
        break;
      }
      radius /= decrease;
      decrease *= 2.0;
      successful = false;
      continue;
    }
    invalid = 0;
    for (std::size_t i = 0; i < nz_; ++i) delta_[i] = step_[i] * scale_[i];
    bool first_accepted = false;
    double cand_cost = 0.0;
    const double a = line_search(z_, cost, grad_, delta_, &first_accepted, &cand_cost);
    if (a != 1.0) {
      for (double& d : delta_) d *= a;
    }
    for (std::size_t i = 0; i < nz_; ++i) cand_[i] = z_[i] + delta_[i];
    project(cand_);
    // With the full step accepted at once, cand_ is the line search's first point (same arithmetic).
    if (!first_accepted) cand_cost = evaluate(cand_, Mode::kCost, grad_trial_, htrial_);
    if (!std::isfinite(cand_cost)) cand_cost = std::numeric_limits<double>::max();
    double step_norm = 0.0;
    for (std::size_t i = 0; i < nz_; ++i) step_norm += (z_[i] - cand_[i]) * (z_[i] - cand_[i]);
    if (std::sqrt(step_norm) <= kParameterTolerance * (x_norm + kParameterTolerance)) {
      sum.converged = true;
      break;
    }
    if (std::abs(cost - cand_cost) <= p_->function_tolerance * cost) {
      sum.converged = true;
      break;
    }
    const double rho = (cost - cand_cost) / model_change;
    if (rho > kMinRelativeDecrease) {
      z_.swap(cand_);
      x_norm = norm(z_);
      if (first_accepted) {
        cost = cand_cost;
        grad_.swap(grad_trial_);
        hband_.swap(htrial_);
      } else {
        cost = evaluate(z_, Mode::kFull, grad_, hband_);
      }
      gmax = projected_gradient_max_norm();
      radius = std::min(kMaxRadius, radius / std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3)));
      decrease = 2.0;
      successful = true;
      ++sum.successful_steps;
    } else {
      radius /= decrease;
      decrease *= 2.0;
      successful = false;
    }
  }
  sum.iterations = iteration;
  sum.final_cost = cost;
  unbind(x, dt);
  if (summary != nullptr) *summary = sum;
  return ok && std::isfinite(cost);
}

}  // namespace bipednav::planning::local
