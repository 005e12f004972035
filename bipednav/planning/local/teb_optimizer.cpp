#include "bipednav/planning/local/teb_optimizer.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <memory>
#include <type_traits>
#include <utility>

#include "bipednav/common/angles.hpp"
#include "bipednav/planning/local/teb_lm.hpp"
#include "bipednav/planning/local/teb_residuals.hpp"

namespace bipednav::planning::local {

namespace {

using Weights = TebWeights;
using Context = TebResidualContext;

// Ceres cost functors over the residual blocks of teb_residuals.hpp (automatic Jacobians).
struct EdgeFunctor {
  Context c;
  template <typename T>
  bool operator()(const T* a, const T* b, const T* dt, T* r) const {
    edge_residuals(c, a, b, dt, r);
    return true;
  }
};

struct AccFunctor {
  Context c;
  template <typename T>
  bool operator()(const T* a, const T* b, const T* d, const T* dt1, const T* dt2, T* r) const {
    acc_residuals(c, a, b, d, dt1, dt2, r);
    return true;
  }
};

struct StartAccFunctor {
  Context c;
  Twist v0;
  template <typename T>
  bool operator()(const T* a, const T* b, const T* dt, T* r) const {
    start_acc_residuals(c, v0, a, b, dt, r);
    return true;
  }
};

// One pose against its associated nearest obstacles (padded with zeros).
struct ObstacleFunctor {
  Context c;
  const std::vector<Obstacle>* obstacles;
  const std::vector<int>* assoc;
  template <typename T>
  bool operator()(const T* p, T* r) const {
    const int k = c.params->obstacles_per_pose;
    for (int i = 0; i < k; ++i) {
      r[i] = T(0.0);
      if (i >= static_cast<int>(assoc->size())) continue;
      r[i] = obstacle_residual(c, (*obstacles)[static_cast<std::size_t>((*assoc)[i])], p);
    }
    return true;
  }
};

// One pose (at a fixed time) against every moving obstacle's prediction.
struct DynamicObstacleFunctor {
  Context c;
  const std::vector<TebMovingObstacle>* moving;
  double t_s;
  template <typename T>
  bool operator()(const T* p, T* r) const {
    for (std::size_t j = 0; j < moving->size(); ++j) r[j] = dynamic_obstacle_residual(c, (*moving)[j], t_s, p);
    return true;
  }
};

struct ViaFunctor {
  Context c;
  Eigen::Vector2d via;
  template <typename T>
  bool operator()(const T* p, T* r) const {
    via_residuals(c, via, p, r);
    return true;
  }
};

// Wraps an automatic-differentiation cost function (parameter blocks of sizes Ns) and remembers its last
// Jacobian evaluation. With the dT lower bounds, Ceres' trust region runs a projected line search every
// iteration; the search evaluates the gradient (all Jacobians) at the point it accepts, and a successful step
// evaluates the Jacobians at that point once more. That second evaluation returns the first's residuals and
// Jacobians: the same function of bitwise the same parameters, so the same bits. Evaluations without
// Jacobians always go to the wrapped function (its double evaluation rounds differently from the Jets'
// values, so they are neither served nor stored). Not thread-safe: one problem is solved by one thread.
template <int R, int... Ns>
class MemoJacobians final : public ceres::CostFunction {
 public:
  explicit MemoJacobians(ceres::CostFunction* inner) : inner_(inner) {
    set_num_residuals(inner->num_residuals());
    *mutable_parameter_block_sizes() = inner->parameter_block_sizes();
    if constexpr (R == ceres::DYNAMIC) out_.resize(static_cast<std::size_t>(num_residuals()) * (1 + kParams));
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    if (jacobians == nullptr) return inner_->Evaluate(parameters, residuals, nullptr);
    const std::size_t nr =
        R == ceres::DYNAMIC ? static_cast<std::size_t>(num_residuals()) : static_cast<std::size_t>(R);
    if (valid_ && hit(kIdx, parameters, jacobians)) {
      std::memcpy(residuals, out_.data(), nr * sizeof(double));
      load(kIdx, nr, jacobians);
      return true;
    }
    valid_ = false;
    if (!inner_->Evaluate(parameters, residuals, jacobians)) return false;
    std::memcpy(out_.data(), residuals, nr * sizeof(double));
    store(kIdx, nr, parameters, jacobians);
    valid_ = true;
    return true;
  }

 private:
  static constexpr std::size_t kBlocks = sizeof...(Ns);
  static constexpr std::size_t kParams = (static_cast<std::size_t>(Ns) + ...);
  static constexpr std::array<std::size_t, kBlocks> kSizes{static_cast<std::size_t>(Ns)...};
  static constexpr std::array<std::size_t, kBlocks> kOffsets = [] {
    std::array<std::size_t, kBlocks> o{};
    for (std::size_t b = 1; b < kBlocks; ++b) o[b] = o[b - 1] + kSizes[b - 1];
    return o;
  }();
  static constexpr auto kIdx = std::make_index_sequence<kBlocks>{};
  using Out =
      std::conditional_t<R == ceres::DYNAMIC, std::vector<double>,
                         std::array<double, static_cast<std::size_t>(R == ceres::DYNAMIC ? 1 : R) * (1 + kParams)>>;

  // The stored evaluation is at bitwise these parameters and holds every Jacobian block asked for.
  template <std::size_t... B>
  bool hit(std::index_sequence<B...>, double const* const* parameters, double** jacobians) const {
    return ((jacobians[B] == nullptr || stored_[B]) && ...) &&
           ((std::memcmp(parameters[B], x_.data() + kOffsets[B], kSizes[B] * sizeof(double)) == 0) && ...);
  }
  template <std::size_t... B>
  void load(std::index_sequence<B...>, std::size_t nr, double** jacobians) const {
    const double* J = out_.data() + nr;
    ((jacobians[B] != nullptr ? (void)std::memcpy(jacobians[B], J + nr * kOffsets[B], nr * kSizes[B] * sizeof(double))
                              : void()),
     ...);
  }
  template <std::size_t... B>
  void store(std::index_sequence<B...>, std::size_t nr, double const* const* parameters, double** jacobians) const {
    double* J = out_.data() + nr;
    ((std::memcpy(x_.data() + kOffsets[B], parameters[B], kSizes[B] * sizeof(double)),
      stored_[B] = jacobians[B] != nullptr,
      stored_[B] ? (void)std::memcpy(J + nr * kOffsets[B], jacobians[B], nr * kSizes[B] * sizeof(double)) : void()),
     ...);
  }

  std::unique_ptr<ceres::CostFunction> inner_;
  mutable std::array<double, kParams> x_{};  // the parameters of the stored evaluation
  mutable Out out_{};                        // its residuals, then its Jacobian blocks (row-major)
  mutable std::array<bool, kBlocks> stored_{};
  mutable bool valid_ = false;
};

// new MemoJacobians around new AutoDiffCostFunction<Functor, R, Ns...>(f[, num_residuals]).
template <typename Functor, int R, int... Ns>
ceres::CostFunction* memo_autodiff(Functor* f, int num_residuals = R) {
  if constexpr (R == ceres::DYNAMIC) {
    return new MemoJacobians<R, Ns...>(new ceres::AutoDiffCostFunction<Functor, R, Ns...>(f, num_residuals));
  } else {
    return new MemoJacobians<R, Ns...>(new ceres::AutoDiffCostFunction<Functor, R, Ns...>(f));
  }
}

// Nearest inner pose of the band for each via point (ordered along the band).
std::vector<std::pair<std::size_t, Eigen::Vector2d>> assign_via_points(const std::vector<double>& x, std::size_t n,
                                                                       const std::vector<Eigen::Vector2d>& via) {
  std::vector<std::pair<std::size_t, Eigen::Vector2d>> out;
  if (n < 3) return out;
  std::size_t from = 1;
  for (const auto& v : via) {
    std::size_t best = from;
    double bd = 1e300;
    for (std::size_t k = from; k + 1 < n; ++k) {
      const double d = std::hypot(x[3 * k] - v.x(), x[3 * k + 1] - v.y());
      if (d < bd) bd = d, best = k;
    }
    out.emplace_back(best, v);
    from = best;
  }
  return out;
}

ceres::LinearSolverType solver_type(const std::string& name) {
  if (name == "dense_normal_cholesky") return ceres::DENSE_NORMAL_CHOLESKY;
  if (name == "dense_qr") return ceres::DENSE_QR;
  if (name == "dense_schur") return ceres::DENSE_SCHUR;
  return ceres::SPARSE_NORMAL_CHOLESKY;
}

// One Levenberg-Marquardt solve over the band stored in x (3 per pose) and dt.
bool solve_once(std::vector<double>& x, std::vector<double>& dt, const TebProblemInput& input,
                std::vector<std::vector<int>>& assoc, const std::vector<std::pair<std::size_t, Eigen::Vector2d>>& via,
                const std::vector<TebMovingObstacle>& moving, const std::vector<double>& times, const Context& ctx,
                const TebBandParams& bp) {
  const std::size_t n = dt.size() + 1;
  // Without construction checks (parameter block sizes, duplicates, aliasing): every block here is distinct.
  ceres::Problem::Options po;
  po.disable_all_safety_checks = true;
  ceres::Problem problem(po);
  for (std::size_t k = 0; k < n; ++k) problem.AddParameterBlock(&x[3 * k], 3);
  for (std::size_t k = 0; k + 1 < n; ++k) {
    problem.AddParameterBlock(&dt[k], 1);
    problem.SetParameterLowerBound(&dt[k], 0, bp.dt_min_s);
  }
  problem.SetParameterBlockConstant(&x[0]);
  problem.SetParameterBlockConstant(&x[3 * (n - 1)]);
  for (std::size_t k = 0; k + 1 < n; ++k) {
    problem.AddResidualBlock(memo_autodiff<EdgeFunctor, 5, 3, 3, 1>(new EdgeFunctor{ctx}), nullptr, &x[3 * k],
                             &x[3 * k + 3], &dt[k]);
  }
  for (std::size_t k = 0; k + 2 < n; ++k) {
    problem.AddResidualBlock(memo_autodiff<AccFunctor, 2, 3, 3, 3, 1, 1>(new AccFunctor{ctx}), nullptr, &x[3 * k],
                             &x[3 * k + 3], &x[3 * k + 6], &dt[k], &dt[k + 1]);
  }
  problem.AddResidualBlock(memo_autodiff<StartAccFunctor, 2, 3, 3, 1>(new StartAccFunctor{ctx, input.start_velocity}),
                           nullptr, &x[0], &x[3], &dt[0]);
  const int kobs = ctx.params->obstacles_per_pose;
  if (input.obstacles != nullptr && kobs > 0) {
    for (std::size_t k = 1; k + 1 < n; ++k) {
      if (assoc[k].empty()) continue;
      auto* f = new ObstacleFunctor{ctx, input.obstacles, &assoc[k]};
      problem.AddResidualBlock(memo_autodiff<ObstacleFunctor, ceres::DYNAMIC, 3>(f, kobs), nullptr, &x[3 * k]);
    }
  }
  if (!moving.empty()) {
    const int m = static_cast<int>(moving.size());
    for (std::size_t k = 1; k + 1 < n; ++k) {
      auto* f = new DynamicObstacleFunctor{ctx, &moving, times[k]};
      problem.AddResidualBlock(memo_autodiff<DynamicObstacleFunctor, ceres::DYNAMIC, 3>(f, m), nullptr, &x[3 * k]);
    }
  }
  for (const auto& [k, v] : via) {
    problem.AddResidualBlock(memo_autodiff<ViaFunctor, 2, 3>(new ViaFunctor{ctx, v}), nullptr, &x[3 * k]);
  }
  ceres::Solver::Options opt;
  opt.minimizer_type = ceres::TRUST_REGION;
  opt.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  opt.linear_solver_type = solver_type(ctx.params->linear_solver);
  opt.max_num_iterations = ctx.params->no_inner_iterations;
  opt.function_tolerance = ctx.params->function_tolerance;
  opt.num_threads = 1;
  opt.logging_type = ceres::SILENT;
  opt.minimizer_progress_to_stdout = false;
  const TebOptimizerParams& p = *ctx.params;
  // Cubic: cost-only bisection took fewer Jacobians but lost closed-loop runs, quadratic gave far worse bands.
  opt.line_search_interpolation_type = ceres::CUBIC;
  if (p.ceres_sparse_library == "eigen_sparse") opt.sparse_linear_algebra_library_type = ceres::EIGEN_SPARSE;
  ceres::Solver::Summary summary;
  ceres::Solve(opt, &problem, &summary);
  return summary.termination_type != ceres::FAILURE && std::isfinite(summary.final_cost);
}

void associate(const std::vector<double>& x, std::size_t n, const TebProblemInput& input, const TebOptimizerParams& p,
               std::vector<std::vector<int>>& assoc, std::vector<std::pair<double, int>>& candidates) {
  assoc.assign(n, {});
  if (input.obstacles == nullptr) return;
  for (std::size_t k = 1; k + 1 < n; ++k) {
    assoc[k] = nearest_obstacles(*input.obstacles, {x[3 * k], x[3 * k + 1]}, p.obstacles_per_pose,
                                 p.obstacle_influence_dist_m, &candidates);
  }
}

}  // namespace

std::vector<TebMovingObstacle> band_moving_obstacles(const TebProblemInput& input, const TebOptimizerParams& params) {
  std::vector<TebMovingObstacle> out;
  if (!params.dynamic_obstacles || input.moving == nullptr) return out;
  for (const auto& o : *input.moving) {
    if (o.usable()) out.push_back(o);
  }
  return out;
}

std::vector<double> band_pose_times(const std::vector<double>& dt_s, double max_s) {
  std::vector<double> t(dt_s.size() + 1, 0.0);
  double sum = 0.0;
  for (std::size_t k = 0; k < dt_s.size(); ++k) {
    sum += dt_s[k];
    t[k + 1] = std::min(sum, max_s);
  }
  return t;
}

bool optimize_band(TebBand& band, const TebProblemInput& input, const TebLimits& limits,
                   const TebBandParams& band_params, const TebOptimizerParams& params) {
  if (band.size() < 2) return false;
  Weights w = base_weights(params);
  const Context ctx{&limits, &params, &w};
  TebBand work = band;
  std::vector<double> x, dt;
  std::vector<std::vector<int>> assoc;
  std::vector<std::pair<double, int>> candidates;  // nearest_obstacles' buffer
  const bool banded = params.linear_solver == "banded_lm";
  TebLmSolver lm;  // its buffers are reused over the outer iterations
  const std::vector<TebMovingObstacle> moving = band_moving_obstacles(input, params);
  std::vector<double> times;
  for (int outer = 0; outer < params.no_outer_iterations; ++outer) {
    resample_band(work, band_params);
    const std::size_t n = work.size();
    x.resize(3 * n);
    for (std::size_t k = 0; k < n; ++k) {
      x[3 * k] = work.poses[k].x, x[3 * k + 1] = work.poses[k].y, x[3 * k + 2] = work.poses[k].theta;
    }
    dt = work.dt_s;
    associate(x, n, input, params, assoc, candidates);
    const auto via = assign_via_points(x, n, input.via_points);
    // The poses' times are the band's at the solve's set-up, held fixed during it (as teb_local_planner).
    if (!moving.empty()) times = band_pose_times(dt, params.dynamic_obstacle_max_prediction_s);
    if (banded) {
      TebLmProblem lp;
      lp.ctx = ctx;
      lp.obstacles = input.obstacles;
      lp.assoc = &assoc;
      lp.via = &via;
      if (!moving.empty()) lp.moving = &moving, lp.pose_times = &times;
      lp.start_velocity = input.start_velocity;
      lp.dt_min_s = band_params.dt_min_s;
      lp.max_iterations = params.no_inner_iterations;
      lp.function_tolerance = params.function_tolerance;
      if (!lm.solve(lp, x, dt)) return false;
    } else if (!solve_once(x, dt, input, assoc, via, moving, times, ctx, band_params)) {
      return false;
    }
    for (std::size_t k = 0; k < n; ++k) work.poses[k] = {x[3 * k], x[3 * k + 1], normalize_angle(x[3 * k + 2])};
    work.dt_s = dt;
    w.obstacle *= params.weight_adapt_factor;  // weight adaptation between outer iterations
    w.dynamic_obstacle *= params.weight_adapt_factor;
    w.nh *= params.weight_adapt_factor;
  }
  for (const auto& p : work.poses) {
    if (!p.is_finite()) return false;
  }
  band = std::move(work);
  return true;
}

BandCost evaluate_band(const TebBand& band, const TebProblemInput& input, const TebLimits& limits,
                       const TebOptimizerParams& params) {
  BandCost c;
  const Weights w = base_weights(params);
  const double eps = params.penalty_epsilon, g = params.sign_gain;
  const auto& s = band.poses;
  const auto sq = [](double v) { return v * v; };
  std::vector<double> v(band.dt_s.size()), om(band.dt_s.size());
  for (std::size_t k = 0; k < band.dt_s.size(); ++k) {
    const double dt = band.dt_s[k];
    const double h = nonholonomic_error(s[k].x, s[k].y, s[k].theta, s[k + 1].x, s[k + 1].y, s[k + 1].theta);
    c.max_nh_error = std::max(c.max_nh_error, std::abs(h));
    c.kinematics += w.nh * sq(h) + w.back * sq(backwards_error(s[k].x, s[k].y, s[k].theta, s[k + 1].x, s[k + 1].y));
    v[k] = linear_velocity(s[k].x, s[k].y, s[k].theta, s[k + 1].x, s[k + 1].y, dt, g);
    om[k] = angular_velocity(s[k].theta, s[k + 1].theta, dt);
    c.velocity += w.vel_x * sq(penalty_interval(v[k], -limits.velocity.max_vel_x_backwards_mps,
                                                limits.velocity.max_vel_x_mps, eps)) +
                  w.vel_th * sq(penalty_symmetric(om[k], limits.velocity.max_vel_theta_radps, eps));
    c.time += w.time * sq(dt);
    c.duration_s += dt;
  }
  for (std::size_t k = 0; k + 1 < v.size(); ++k) {
    const double a = acceleration(v[k], v[k + 1], band.dt_s[k], band.dt_s[k + 1]);
    const double aw = acceleration(om[k], om[k + 1], band.dt_s[k], band.dt_s[k + 1]);
    c.acceleration += w.acc_x * sq(penalty_symmetric(a, limits.velocity.acc_lim_x_mps2, eps)) +
                      w.acc_th * sq(penalty_symmetric(aw, limits.velocity.acc_lim_theta_radps2, eps));
  }
  if (input.obstacles != nullptr) {
    std::vector<std::pair<double, int>> candidates;  // nearest_obstacles' buffer
    for (std::size_t k = 1; k + 1 < s.size(); ++k) {
      for (const int i : nearest_obstacles(*input.obstacles, s[k].position(), params.obstacles_per_pose,
                                           params.obstacle_influence_dist_m, &candidates)) {
        const double d = obstacle_distance((*input.obstacles)[static_cast<std::size_t>(i)], s[k].x, s[k].y);
        c.min_obstacle_dist_m = std::min(c.min_obstacle_dist_m, d);
        c.obstacle += w.obstacle * sq(penalty_below(d, limits.min_obstacle_dist_m, eps));
      }
    }
  }
  const std::vector<TebMovingObstacle> moving = band_moving_obstacles(input, params);
  if (!moving.empty()) {
    const auto times = band_pose_times(band.dt_s, params.dynamic_obstacle_max_prediction_s);
    for (std::size_t k = 1; k + 1 < s.size(); ++k) {
      for (const auto& o : moving) {
        const double d = o.distance(s[k].position(), times[k]);
        c.min_dynamic_dist_m = std::min(c.min_dynamic_dist_m, d - o.radius_m);
        c.dynamic_obstacle += w.dynamic_obstacle * sq(penalty_below(d, o.bound(times[k]), eps));
      }
    }
  }
  for (const auto& via : input.via_points) {
    double best = 1e300;
    for (const auto& p : s) best = std::min(best, (p.position() - via).squaredNorm());
    c.viapoint += w.via * best;
  }
  return c;
}

}  // namespace bipednav::planning::local
