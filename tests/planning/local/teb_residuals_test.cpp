#include "bipednav/planning/local/teb_residuals.hpp"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cstring>
#include <numbers>
#include <random>

#include "bipednav/planning/local/teb_lm.hpp"
#include "bipednav/planning/local/teb_optimizer.hpp"
#include "teb_trials.hpp"

namespace bipednav::planning::local {

namespace {

using Jet = ceres::Jet<double, 11>;

struct Fixture {
  TebLimits lim;
  TebOptimizerParams op;
  TebWeights w;
  TebResidualContext ctx;
  Fixture() : w(base_weights(op)), ctx{&lim, &op, &w} {
    // Distinct weights so a mixed-up term shows.
    w = {1000.0, 2.5, 2.0, 1.5, 1.2, 0.7, 1.0, 80.0, 3.0, 65.0};
  }
};

// The polygon distance with every edge's distance in T, as distance_to_polygon computed it before it
// compared the edges on their scalar parts: the reference its Jets must equal bit for bit.
template <typename T>
T distance_to_polygon_all_edges(const T& px, const T& py, const std::vector<Eigen::Vector2d>& v) {
  if (v.size() == 1) return distance_to_point(px, py, v[0]);
  if (v.size() == 2) return distance_to_segment(px, py, v[0], v[1]);
  bool inside = true;
  T best = distance_to_segment(px, py, v.back(), v.front());
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Eigen::Vector2d& a = v[i];
    const Eigen::Vector2d& b = v[(i + 1) % v.size()];
    const T cross = T(b.x() - a.x()) * (py - T(a.y())) - T(b.y() - a.y()) * (px - T(a.x()));
    if (cross < T(0.0)) inside = false;
    if (i + 1 < v.size()) {
      const T d = distance_to_segment(px, py, a, b);
      if (d < best) best = d;
    }
  }
  return inside ? -best : best;
}

// Jets for the variables vars[0..n): value and unit derivative.
std::vector<Jet> jets(const std::vector<double>& vars) {
  std::vector<Jet> j(vars.size());
  for (std::size_t i = 0; i < vars.size(); ++i) j[i] = Jet(vars[i], static_cast<int>(i));
  return j;
}

void expect_jacobian(const Jet* rj, const double* r, const double* J, int m, int cols, const std::string& what) {
  for (int i = 0; i < m; ++i) {
    EXPECT_NEAR(r[i], rj[i].a, 1e-12 * std::max(1.0, std::abs(rj[i].a))) << what << " r" << i;
    for (int j = 0; j < cols; ++j)
      EXPECT_NEAR(J[i * cols + j], rj[i].v[j], 1e-9 * std::max(1.0, std::abs(rj[i].v[j])))
          << what << " d r" << i << " / d v" << j;
  }
}

// Random pose pairs, some placed so that a penalty sits just at its kink.
struct Sampler {
  std::mt19937 rng{7};
  double u(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
};

}  // namespace

TEST(TebResiduals, EdgeJacobianMatchesAutodiff) {
  Fixture f;
  Sampler s;
  const double eps = f.op.penalty_epsilon;
  for (int trial = 0; trial < 400; ++trial) {
    double a[3] = {s.u(-2, 2), s.u(-2, 2), s.u(-4, 4)};
    const double len = s.u(0.0, 0.4), dir = s.u(-3.2, 3.2);
    double b[3] = {a[0] + len * std::cos(dir), a[1] + len * std::sin(dir), a[2] + s.u(-1.5, 1.5)};
    double dt = s.u(0.05, 0.8);
    switch (trial % 5) {
      case 1:  // linear velocity just past the forward limit's kink
        dt = len / (f.lim.velocity.max_vel_x_mps - eps + (trial % 2 ? 1e-7 : -1e-7));
        b[0] = a[0] + len * std::cos(a[2]), b[1] = a[1] + len * std::sin(a[2]);
        break;
      case 2:  // forward projection near zero (backwards kink, smooth sign's steep part)
        b[0] = a[0] + len * std::cos(a[2] + M_PI / 2 + 1e-6 * (trial % 3 - 1));
        b[1] = a[1] + len * std::sin(a[2] + M_PI / 2 + 1e-6 * (trial % 3 - 1));
        break;
      case 3:  // angular velocity at its kink
        b[2] = a[2] + (f.lim.velocity.max_vel_theta_radps - eps + 1e-7) * dt;
        break;
      case 4:  // coincident positions (safe_norm floor)
        b[0] = a[0], b[1] = a[1];
        break;
      default:
        break;
    }
    const auto vj = jets({a[0], a[1], a[2], b[0], b[1], b[2], dt});
    Jet rj[5];
    edge_residuals(f.ctx, &vj[0], &vj[3], &vj[6], rj);
    double r[5], J[35];
    const IntervalVelocity iv = interval_velocity(a, b, dt, f.op.sign_gain);
    edge_jacobian(f.ctx, a, b, dt, iv, r, J);
    expect_jacobian(rj, r, J, 5, 7, "edge trial " + std::to_string(trial));
    if (HasFailure()) return;
  }
}

TEST(TebResiduals, AccelerationJacobiansMatchAutodiff) {
  Fixture f;
  Sampler s;
  int at_kink = 0;
  for (int trial = 0; trial < 400; ++trial) {
    double a[3] = {s.u(-2, 2), s.u(-2, 2), s.u(-3, 3)};
    double b[3] = {a[0] + s.u(-0.3, 0.3), a[1] + s.u(-0.3, 0.3), a[2] + s.u(-1, 1)};
    double d[3] = {b[0] + s.u(-0.3, 0.3), b[1] + s.u(-0.3, 0.3), b[2] + s.u(-1, 1)};
    double dt1 = s.u(0.05, 0.6), dt2 = s.u(0.05, 0.6);
    const IntervalVelocity iv1 = interval_velocity(a, b, dt1, f.op.sign_gain);
    if (trial % 3 == 1) {
      // Put the linear acceleration next to its kink (1e-7 on either side; at the kink itself the two
      // roundings may fall on different sides): choose dt2 so that 2 (v2 - v1) / (dt1 + dt2) = target.
      const double side = trial % 4 == 1 ? 1e-7 : -1e-7;
      const double target = (f.lim.velocity.acc_lim_x_mps2 - f.op.penalty_epsilon + side) * (trial % 2 ? 1.0 : -1.0);
      // acc(dt2) = 2 (n2 sg2 / dt2 - v1) / (dt1 + dt2): solve for dt2 by bisection on [0.001, 100].
      const IntervalVelocity unit = interval_velocity(b, d, 1.0, f.op.sign_gain);  // n2 sg2
      const auto acc_of = [&](double t) { return acceleration(iv1.v, unit.v / t, dt1, t) - target; };
      double lo = 1e-3, hi = 100.0;
      if (acc_of(lo) * acc_of(hi) < 0.0) {
        for (int it = 0; it < 200; ++it) {
          const double mid = 0.5 * (lo + hi);
          (acc_of(mid) * acc_of(lo) > 0.0 ? lo : hi) = mid;
        }
        dt2 = 0.5 * (lo + hi);
        const IntervalVelocity iv2 = interval_velocity(b, d, dt2, f.op.sign_gain);
        if (std::abs(acceleration(iv1.v, iv2.v, dt1, dt2) - target) < 1e-9) ++at_kink;
      }
    }
    const auto vj = jets({a[0], a[1], a[2], b[0], b[1], b[2], d[0], d[1], d[2], dt1, dt2});
    Jet rj[2];
    acc_residuals(f.ctx, &vj[0], &vj[3], &vj[6], &vj[9], &vj[10], rj);
    double r[2], J[22];
    acc_jacobian(f.ctx, iv1, interval_velocity(b, d, dt2, f.op.sign_gain), dt1, dt2, r, J);
    expect_jacobian(rj, r, J, 2, 11, "acc trial " + std::to_string(trial));

    Twist v0;
    v0.linear_x = s.u(-0.3, 0.6), v0.angular_z = s.u(-1, 1);
    const auto vs = jets({a[0], a[1], a[2], b[0], b[1], b[2], dt1});
    start_acc_residuals(f.ctx, v0, &vs[0], &vs[3], &vs[6], rj);
    double J7[14];
    start_acc_jacobian(f.ctx, v0, iv1, dt1, r, J7);
    expect_jacobian(rj, r, J7, 2, 7, "start acc trial " + std::to_string(trial));
    if (HasFailure()) return;
  }
  EXPECT_GT(at_kink, 40);  // of 133 attempts: enough samples sit 1e-7 from the kink
}

TEST(TebResiduals, ObstacleGradientMatchesAutodiff) {
  Fixture f;
  Sampler s;
  std::vector<Obstacle> obs(4);
  obs[0].vertices = {{0.3, 0.2}};
  obs[1].vertices = {{-0.5, 0.0}, {0.5, 0.4}};
  obs[2].vertices = {{0.0, 0.0}, {0.6, 0.0}, {0.6, 0.5}, {0.0, 0.5}};  // ccw square
  obs[3].vertices = {{1.0, 1.0}, {1.0 + 1e-10, 1.0}};                  // degenerate segment
  for (int trial = 0; trial < 800; ++trial) {
    const Obstacle& o = obs[static_cast<std::size_t>(trial) % obs.size()];
    double p[2] = {s.u(-1.0, 1.5), s.u(-1.0, 1.5)};
    if (trial % 7 == 3) {
      // Near the penalty's kink: at distance rho + eps from a point obstacle.
      const double ang = s.u(-3, 3), rr = f.lim.min_obstacle_dist_m + f.op.penalty_epsilon + 1e-7;
      p[0] = obs[0].vertices[0].x() + rr * std::cos(ang), p[1] = obs[0].vertices[0].y() + rr * std::sin(ang);
    }
    const auto pj = jets({p[0], p[1], 0.0});
    const Jet rj = obstacle_residual(f.ctx, o, pj.data());
    double g[2];
    const double d = obstacle_distance_gradient(o, p[0], p[1], g);
    EXPECT_NEAR(d, obstacle_distance(o, p[0], p[1]), 1e-12);
    const double bound = f.lim.min_obstacle_dist_m + f.op.penalty_epsilon;
    const double wo = std::sqrt(f.w.obstacle);
    const double r = wo * penalty_below(d, f.lim.min_obstacle_dist_m, f.op.penalty_epsilon);
    const double J[2] = {d < bound ? -wo * g[0] : 0.0, d < bound ? -wo * g[1] : 0.0};
    expect_jacobian(&rj, &r, J, 1, 2, "obstacle trial " + std::to_string(trial));
    if (HasFailure()) return;
  }
}

namespace {

using Jet3 = ceres::Jet<double, 3>;

// Bitwise equal values and derivatives (signed zeros and NaNs included).
bool same_bits(const Jet3& x, const Jet3& y) {
  return std::memcmp(&x.a, &y.a, sizeof(double)) == 0 && std::memcmp(x.v.data(), y.v.data(), 3 * sizeof(double)) == 0;
}

}  // namespace

// The Jet polygon distance compares the edges on their scalar parts and differentiates the nearest one only;
// obstacle_residual and dynamic_obstacle_residual return zero on the scalar part alone beyond their bounds.
// Both must give bitwise the Jets of the full per-edge evaluation (the optimiser's results depend on every bit),
// ties between edges included (a square's centre and corner diagonals: several edges at one distance).
TEST(TebResiduals, JetObstacleShortcutsMatchFullJets) {
  Fixture f;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double wo = std::sqrt(f.w.obstacle), wd = std::sqrt(f.w.dynamic_obstacle);
  const double eps = f.op.penalty_epsilon, rho = f.lim.min_obstacle_dist_m;
  int zero = 0, penalised = 0;
  const auto check = [&](const std::vector<Eigen::Vector2d>& v, double px, double py) {
    const Jet3 x(px, 0), y(py, 1);
    const Jet3 full = distance_to_polygon_all_edges(x, y, v);
    EXPECT_TRUE(same_bits(distance_to_polygon(x, y, v), full)) << px << " " << py << " " << v.size();
    Obstacle o;
    o.vertices = v;
    EXPECT_EQ(jet_value_obstacle_distance(o, px, py), full.a);
    const Jet3 p[3] = {x, y, Jet3(0.3, 2)};
    const Jet3 ref = wo * penalty_below(full, rho, eps);
    EXPECT_TRUE(same_bits(obstacle_residual(f.ctx, o, p), ref)) << px << " " << py;
    ++(ref.a == 0.0 ? zero : penalised);
  };
  for (int t = 0; t < 3000; ++t) {
    const int k = 1 + static_cast<int>(rng() % 10);
    const Eigen::Vector2d c(5 * u(rng), 5 * u(rng));
    const double r = t % 3 == 0 ? 0.05 + 0.2 * std::abs(u(rng)) : 0.02 + std::abs(u(rng));
    std::vector<Eigen::Vector2d> v;
    for (int i = 0; i < k; ++i) {
      const double a = 2 * std::numbers::pi * i / k + 0.1 * u(rng);
      v.emplace_back(c.x() + r * std::cos(a), c.y() + r * std::sin(a));
    }
    if (t % 10 == 0 && k >= 2) v[1] = v[0];  // a degenerate edge
    for (int q = 0; q < 6; ++q) {
      const double s = q < 3 ? 2 * r : r + rho + 2 * eps;
      check(v, c.x() + s * u(rng), c.y() + s * u(rng));
    }
    check(v, v[0].x(), v[0].y());
  }
  // Exact ties: a square's centre (four edges) and points on the diagonals beyond its corners (two edges).
  const std::vector<Eigen::Vector2d> sq{{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}};
  check(sq, 0.0, 0.0);
  for (const double s : {0.01, 0.05, 0.1, 0.2, 0.3})
    for (const auto& corner : sq) check(sq, corner.x() * (1 + 2 * s), corner.y() * (1 + 2 * s));
  EXPECT_GT(zero, 1000);
  EXPECT_GT(penalised, 1000);
  // Moving obstacles: a point prediction and a swept segment, the pose near and beyond the bound.
  for (int t = 0; t < 3000; ++t) {
    TebMovingObstacle o;
    o.position = {u(rng), u(rng)};
    o.velocity = {u(rng), u(rng)};
    o.clearance_m = 0.3 + 0.3 * std::abs(u(rng));
    o.growth_mps = 0.1 * std::abs(u(rng));
    o.lead_s = t % 2 == 0 ? 0.0 : std::abs(u(rng));
    const double ts = 2.0 * std::abs(u(rng));
    const Jet3 p[3] = {Jet3(1.5 * u(rng), 0), Jet3(1.5 * u(rng), 1), Jet3(0.1, 2)};
    const Jet3 d = o.lead_s > 0.0 ? distance_to_segment(p[0], p[1], o.at(ts), o.lead_end(ts))
                                  : distance_to_point(p[0], p[1], o.at(ts));
    const Jet3 ref = wd * penalty_below(d, o.bound(ts), eps);
    EXPECT_TRUE(same_bits(dynamic_obstacle_residual(f.ctx, o, ts, p), ref)) << t;
  }
}

// edge_residuals computes each heading's cosine and sine once for the non-holonomic, backwards and velocity
// terms: bitwise the residuals and derivatives of each term computing its own (the formulas written out here).
TEST(TebResiduals, EdgeResidualsSharedHeadingsMatchPerTermTrig) {
  Fixture f;
  Sampler s;
  using std::cos;
  using std::sin;
  using std::sqrt;
  const auto bits = [](const Jet& x, const Jet& y) {
    return std::memcmp(&x.a, &y.a, sizeof(double)) == 0 &&
           std::memcmp(x.v.data(), y.v.data(), Jet::DIMENSION * sizeof(double)) == 0;
  };
  for (int trial = 0; trial < 2000; ++trial) {
    const auto j = jets({s.u(-2, 2), s.u(-2, 2), s.u(-4, 4), s.u(-2, 2), s.u(-2, 2), s.u(-4, 4), s.u(0.01, 0.5)});
    const Jet *a = &j[0], *b = &j[3], *dt = &j[6];
    Jet r[5];
    edge_residuals(f.ctx, a, b, dt, r);
    const Jet dx = b[0] - a[0], dy = b[1] - a[1];
    const Jet nh = (cos(a[2]) + cos(b[2])) * dy - (sin(a[2]) + sin(b[2])) * dx;
    const Jet back = penalty_below(Jet(cos(a[2]) * (b[0] - a[0]) + sin(a[2]) * (b[1] - a[1])), 0.0, 0.0);
    const Jet forward = cos(a[2]) * dx + sin(a[2]) * dy;
    const Jet v = safe_norm(dx, dy) / dt[0] * smooth_sign(forward, f.op.sign_gain);
    EXPECT_TRUE(bits(r[0], sqrt(f.w.nh) * nh)) << trial;
    EXPECT_TRUE(bits(r[1], sqrt(f.w.back) * back)) << trial;
    const double eps = f.op.penalty_epsilon;
    EXPECT_TRUE(bits(r[2], sqrt(f.w.vel_x) * penalty_interval(v, -f.lim.velocity.max_vel_x_backwards_mps,
                                                              f.lim.velocity.max_vel_x_mps, eps)))
        << trial;
    // The double forms (evaluate_band's) give the Jets' values (no quotient in these two).
    double rd[5];
    const double ad[3] = {a[0].a, a[1].a, a[2].a}, bd[3] = {b[0].a, b[1].a, b[2].a}, dtd = dt[0].a;
    edge_residuals(f.ctx, ad, bd, &dtd, rd);
    EXPECT_EQ(rd[0], r[0].a);
    EXPECT_EQ(rd[1], r[1].a);
    EXPECT_EQ(
        nonholonomic_error(ad[0], ad[1], ad[2], bd[0], bd[1], bd[2]),
        (std::cos(ad[2]) + std::cos(bd[2])) * (bd[1] - ad[1]) - (std::sin(ad[2]) + std::sin(bd[2])) * (bd[0] - ad[0]));
    if (HasFailure()) return;
  }
}

// The whole problem's gradient and J^T J of the banded solver against automatic differentiation of the
// residual blocks assembled densely.
TEST(TebLm, GradientAndNormalEquationsMatchAutodiff) {
  Fixture f;
  TebBandParams bp;
  TebBand band = init_band({0, 0, 0.2}, {{1.0, 0.6}}, {2.5, 1.0, -0.3}, f.lim, bp);
  std::mt19937 rng(3);
  std::normal_distribution<double> nd(0.0, 0.05);
  for (std::size_t k = 1; k + 1 < band.size(); ++k) band.poses[k].x += nd(rng), band.poses[k].theta += 5 * nd(rng);
  for (double& dt : band.dt_s) dt *= 0.5 + std::abs(nd(rng)) * 10;
  const std::size_t n = band.size();
  std::vector<double> x(3 * n), dt = band.dt_s;
  for (std::size_t k = 0; k < n; ++k)
    x[3 * k] = band.poses[k].x, x[3 * k + 1] = band.poses[k].y, x[3 * k + 2] = band.poses[k].theta;
  std::vector<Obstacle> obs(1);
  obs[0].vertices = {{1.2, 0.45}};
  std::vector<std::vector<int>> assoc(n);
  for (std::size_t k = 1; k + 1 < n; ++k) assoc[k] = {0};
  const std::vector<std::pair<std::size_t, Eigen::Vector2d>> via{{n / 2, {1.0, 0.6}}};
  TebLmProblem p;
  p.ctx = f.ctx;
  p.obstacles = &obs;
  p.assoc = &assoc;
  p.via = &via;
  p.start_velocity.linear_x = 0.3;
  Eigen::VectorXd g;
  Eigen::MatrixXd H;
  TebLmSolver lm;
  const double cost = lm.evaluate_dense(p, x, dt, &g, &H);

  // Dense reference: column of each free variable (dT_0, s_1, dT_1, ...).
  const auto N = static_cast<int>(4 * n - 7);
  const auto col_pose = [&](std::size_t k, int c) {
    return (k == 0 || k + 1 == n) ? -1 : static_cast<int>(4 * k - 3) + c;
  };
  const auto col_dt = [&](std::size_t k) { return static_cast<int>(4 * k); };
  std::vector<Eigen::VectorXd> rows;
  double ref_cost = 0.0;
  const auto add = [&](const Jet* r, int m, const std::vector<int>& cols) {
    for (int i = 0; i < m; ++i) {
      Eigen::VectorXd row = Eigen::VectorXd::Zero(N + 1);
      row[N] = r[i].a;
      for (std::size_t j = 0; j < cols.size(); ++j)
        if (cols[j] >= 0) row[cols[j]] += r[i].v[static_cast<Eigen::Index>(j)];
      ref_cost += 0.5 * r[i].a * r[i].a;
      rows.push_back(row);
    }
  };
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const auto v = jets({x[3 * k], x[3 * k + 1], x[3 * k + 2], x[3 * k + 3], x[3 * k + 4], x[3 * k + 5], dt[k]});
    const std::vector<int> cols{col_pose(k, 0),     col_pose(k, 1),     col_pose(k, 2), col_pose(k + 1, 0),
                                col_pose(k + 1, 1), col_pose(k + 1, 2), col_dt(k)};
    Jet r[5];
    edge_residuals(f.ctx, &v[0], &v[3], &v[6], r);
    add(r, 5, cols);
    if (k == 0) {
      start_acc_residuals(f.ctx, p.start_velocity, &v[0], &v[3], &v[6], r);
      add(r, 2, cols);
    }
    if (k + 2 < n) {
      const auto v2 = jets({x[3 * k], x[3 * k + 1], x[3 * k + 2], x[3 * k + 3], x[3 * k + 4], x[3 * k + 5],
                            x[3 * k + 6], x[3 * k + 7], x[3 * k + 8], dt[k], dt[k + 1]});
      acc_residuals(f.ctx, &v2[0], &v2[3], &v2[6], &v2[9], &v2[10], r);
      std::vector<int> c2{col_pose(k, 0),     col_pose(k, 1),     col_pose(k, 2),     col_pose(k + 1, 0),
                          col_pose(k + 1, 1), col_pose(k + 1, 2), col_pose(k + 2, 0), col_pose(k + 2, 1),
                          col_pose(k + 2, 2), col_dt(k),          col_dt(k + 1)};
      add(r, 2, c2);
    }
  }
  for (std::size_t k = 1; k + 1 < n; ++k) {
    const auto v = jets({x[3 * k], x[3 * k + 1], x[3 * k + 2]});
    const Jet r = obstacle_residual(f.ctx, obs[0], v.data());
    add(&r, 1, {col_pose(k, 0), col_pose(k, 1), col_pose(k, 2)});
  }
  for (const auto& [k, vp] : via) {
    const auto v = jets({x[3 * k], x[3 * k + 1]});
    Jet r[2];
    via_residuals(f.ctx, vp, v.data(), r);
    add(r, 2, {col_pose(k, 0), col_pose(k, 1)});
  }
  Eigen::MatrixXd Jd(static_cast<Eigen::Index>(rows.size()), N);
  Eigen::VectorXd rd(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t i = 0; i < rows.size(); ++i) {
    Jd.row(static_cast<Eigen::Index>(i)) = rows[i].head(N).transpose();
    rd[static_cast<Eigen::Index>(i)] = rows[i][N];
  }
  EXPECT_NEAR(cost, ref_cost, 1e-9 * ref_cost);
  const Eigen::VectorXd g_ref = Jd.transpose() * rd;
  const Eigen::MatrixXd H_ref = Jd.transpose() * Jd;
  EXPECT_LT((g - g_ref).lpNorm<Eigen::Infinity>(), 1e-9 * std::max(1.0, g_ref.lpNorm<Eigen::Infinity>()));
  EXPECT_LT((H - H_ref).lpNorm<Eigen::Infinity>(), 1e-9 * std::max(1.0, H_ref.lpNorm<Eigen::Infinity>()));
  // The band structure the solver relies on.
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j)
      if (std::abs(i - j) > TebLmSolver::kHalfBandwidth) {
        EXPECT_EQ(H_ref(i, j), 0.0) << i << "," << j;
      }
}

// The banded solver and Ceres minimise the same problem with the same trust-region schedule: the
// optimised bands agree to rounding (not bit for bit: the sums run in another order).
TEST(TebLm, MatchesCeresOnTheSameBands) {
  TebLimits lim;
  TebBandParams bp;
  std::vector<Obstacle> obs(2);
  obs[0].vertices = {{1.5, 0.05}};
  obs[1].vertices = {{2.2, -0.6}, {2.8, -0.6}, {2.8, -0.3}, {2.2, -0.3}};
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int compared = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const auto [in, band] = test::random_teb_trial(trial, rng, u, obs, lim, bp);
    TebOptimizerParams ceres_op, band_op;
    ceres_op.linear_solver = "sparse_normal_cholesky";
    band_op.linear_solver = "banded_lm";
    TebBand b1 = band, b2 = band;
    ASSERT_TRUE(optimize_band(b1, in, lim, bp, ceres_op));
    ASSERT_TRUE(optimize_band(b2, in, lim, bp, band_op));
    ASSERT_EQ(b1.size(), b2.size());
    const double c1 = evaluate_band(b1, in, lim, ceres_op).selection();
    const double c2 = evaluate_band(b2, in, lim, band_op).selection();
    EXPECT_NEAR(c1, c2, 1e-9 * std::max(1.0, c1)) << "trial " << trial;
    double dmax = 0.0;
    for (std::size_t k = 0; k < b1.size(); ++k) dmax = std::max(dmax, distance(b1.poses[k], b2.poses[k]));
    EXPECT_LT(dmax, 1e-9) << "trial " << trial;  // 1e-13 m seen
    for (double dt : b2.dt_s) EXPECT_GE(dt, bp.dt_min_s);
    ++compared;
  }
  EXPECT_EQ(compared, 12);
}

// The smallest bands: two poses (only dT_0 free) and three.
TEST(TebLm, MatchesCeresOnTinyBands) {
  TebLimits lim;
  TebBandParams bp;
  bp.min_samples = 2;
  for (const double gx : {0.05, 0.4}) {
    TebBand band;
    band.poses = {{0, 0, 0}, {gx, 0.02, 0.1}};
    band.dt_s = {0.25};  // inside the re-sampling hysteresis; 1.6 m/s for gx = 0.4 (too fast)
    for (int n = 2; n <= 3; ++n) {
      if (n == 3) {
        band.poses.insert(band.poses.begin() + 1, {gx / 2, 0.0, 0.05});
        band.dt_s = {0.25, 0.25};
      }
      TebOptimizerParams ceres_op, band_op;
      ceres_op.linear_solver = "sparse_normal_cholesky";
      band_op.linear_solver = "banded_lm";
      band_op.no_outer_iterations = ceres_op.no_outer_iterations = 1;  // no re-sampling in between
      TebBand b1 = band, b2 = band;
      ASSERT_TRUE(optimize_band(b1, {}, lim, bp, ceres_op));
      ASSERT_TRUE(optimize_band(b2, {}, lim, bp, band_op));
      ASSERT_EQ(b1.size(), static_cast<std::size_t>(n));
      ASSERT_EQ(b2.size(), static_cast<std::size_t>(n));
      EXPECT_NE(b2.dt_s[0], 0.25);  // the solve moved
      for (std::size_t k = 0; k < b1.dt_s.size(); ++k) EXPECT_NEAR(b1.dt_s[k], b2.dt_s[k], 1e-9) << gx << " " << n;
      for (std::size_t k = 0; k < b1.size(); ++k) EXPECT_LT(distance(b1.poses[k], b2.poses[k]), 1e-9);
    }
  }
}

TEST(TebLm, RejectsMalformedInput) {
  Fixture f;
  TebLmProblem p;
  p.ctx = f.ctx;
  TebLmSolver lm;
  std::vector<double> x{0, 0, 0}, dt;
  EXPECT_FALSE(lm.solve(p, x, dt));  // one pose: no interval
  std::vector<double> x2{0, 0, 0, 1, 0, 0}, dt2{std::nan("")};
  EXPECT_FALSE(lm.solve(p, x2, dt2));  // non-finite interval: the cost cannot be evaluated
  std::vector<double> x3{0, 0, 0, 1, 0}, dt3{0.3};
  EXPECT_FALSE(lm.solve(p, x3, dt3));  // size mismatch
}

}  // namespace bipednav::planning::local
