#include "bipednav/planning/local/teb_optimizer.hpp"

#include <gtest/gtest.h>

#include <random>

#include "bipednav/planning/local/teb_planner.hpp"
#include "teb_trials.hpp"

namespace bipednav::planning::local {

TEST(TebOptimizer, ConvergedBandHasSmallNonholonomicResiduals) {
  TebLimits lim;
  TebBandParams bp;
  TebOptimizerParams op;
  op.no_outer_iterations = 4;
  // A lateral offset: the straight-line initialisation violates eq. 5.5 at both ends.
  TebBand band = init_band({0, 0, 0}, {}, {2.0, 1.0, 0.0}, lim, bp);  // h = 0.067 at both ends
  const TebProblemInput in;
  const double before = evaluate_band(band, in, lim, op).max_nh_error;
  ASSERT_TRUE(optimize_band(band, in, lim, bp, op));
  const BandCost after = evaluate_band(band, in, lim, op);
  EXPECT_GT(before, 0.05);
  EXPECT_LT(after.max_nh_error, 0.01) << "before " << before;
  EXPECT_DOUBLE_EQ(band.poses.front().x, 0.0);  // start and goal fixed
  EXPECT_DOUBLE_EQ(band.poses.back().y, 1.0);
  for (double dt : band.dt_s) EXPECT_GE(dt, bp.dt_min_s);
}

TEST(TebOptimizer, PushesTheBandAwayFromAnObstacle) {
  TebLimits lim;
  TebBandParams bp;
  TebOptimizerParams op;
  op.no_outer_iterations = 4;
  std::vector<Obstacle> obs(1);
  obs[0].vertices = {{1.5, 0.05}};
  obs[0].centroid = {1.5, 0.05};
  TebProblemInput in;
  in.obstacles = &obs;
  TebBand band = init_band({0, 0, 0}, {}, {3.0, 0.0, 0.0}, lim, bp);
  ASSERT_TRUE(optimize_band(band, in, lim, bp, op));
  const BandCost c = evaluate_band(band, in, lim, op);
  EXPECT_GT(c.min_obstacle_dist_m, lim.min_obstacle_dist_m - 0.05);
  EXPECT_LT(c.max_nh_error, 0.02);
}

TEST(TebOptimizer, TimeOptimalBandRespectsVelocityLimit) {
  TebLimits lim;
  TebBandParams bp;
  TebOptimizerParams op;
  op.no_outer_iterations = 4;
  TebBand band = init_band({0, 0, 0}, {}, {3.0, 0.0, 0.0}, lim, bp);
  for (double& dt : band.dt_s) dt *= 3.0;  // start far too slow
  ASSERT_TRUE(optimize_band(band, {}, lim, bp, op));
  // Time-optimal: close to 3 m at 0.5 m/s, not much faster (the velocity penalty).
  EXPECT_NEAR(band.duration_s(), 6.0, 0.6);
  const Twist cmd = band_command(band);
  EXPECT_LT(cmd.linear_x, lim.velocity.max_vel_x_mps * 1.1);
}

}  // namespace bipednav::planning::local

namespace bipednav::planning::local {

namespace {

// Twelve bands around a point and a box obstacle (random start headings, goals, via points and
// start speeds; every third starts far from time-optimal), optimised with default options and with op.
struct CeresOptionScene {
  TebLimits lim;
  TebBandParams bp;
  std::vector<Obstacle> obs = std::vector<Obstacle>(2);
  CeresOptionScene() {
    obs[0].vertices = {{1.5, 0.05}};
    obs[0].centroid = {1.5, 0.05};
    obs[1].vertices = {{2.2, -0.6}, {2.8, -0.6}, {2.8, -0.3}, {2.2, -0.3}};
    obs[1].centroid = {2.5, -0.45};
  }
  // Each trial's objective (selection cost) with the default options and with op, and op's bands checked.
  void compare(const TebOptimizerParams& op, double max_rel_objective) const {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const TebOptimizerParams def;
    double sum_def = 0.0, sum_op = 0.0;
    for (int trial = 0; trial < 12; ++trial) {
      const auto [in, band] = test::random_teb_trial(trial, rng, u, obs, lim, bp);
      TebBand b0 = band, b1 = band;
      ASSERT_TRUE(optimize_band(b0, in, lim, bp, def));
      ASSERT_TRUE(optimize_band(b1, in, lim, bp, op)) << "trial " << trial;
      const BandCost c0 = evaluate_band(b0, in, lim, def), c1 = evaluate_band(b1, in, lim, def);
      sum_def += c0.selection(), sum_op += c1.selection();
      // A valid band: finite, start and goal kept, dT above its bound, clear of the obstacles as the
      // default's, the kinematic constraint met.
      for (const auto& p : b1.poses) EXPECT_TRUE(p.is_finite());
      EXPECT_EQ(b1.poses.front().x, band.poses.front().x);
      EXPECT_EQ(b1.poses.back().y, band.poses.back().y);
      for (double dt : b1.dt_s) EXPECT_GE(dt, bp.dt_min_s);
      EXPECT_GT(c1.min_obstacle_dist_m, std::min(c0.min_obstacle_dist_m, lim.min_obstacle_dist_m) - 0.05)
          << "trial " << trial;
      EXPECT_LT(c1.max_nh_error, std::max(0.05, 2.0 * c0.max_nh_error)) << "trial " << trial;
      EXPECT_LT(c1.selection(), (1.0 + max_rel_objective) * c0.selection() + 1e-6) << "trial " << trial;
      EXPECT_NEAR(b1.duration_s(), b0.duration_s(), 0.15 * b0.duration_s()) << "trial " << trial;
    }
    EXPECT_LT(sum_op, (1.0 + max_rel_objective / 4) * sum_def);
  }
};

}  // namespace

// Eigen's sparse Cholesky instead of CHOLMOD factorises the same normal equations: the bands agree to rounding.
TEST(TebOptimizer, EigenSparseCholeskyGivesTheSameBands) {
  TebOptimizerParams op;
  op.ceres_sparse_library = "eigen_sparse";
  CeresOptionScene().compare(op, 1e-6);
}

TEST(TebOptimizer, RejectsUnknownCeresOptions) {
  TebOptimizerParams op;
  op.ceres_sparse_library = "cholmod";
  EXPECT_ANY_THROW(op.validate());
  op.ceres_sparse_library = "eigen_sparse";
  EXPECT_NO_THROW(op.validate());
}

}  // namespace bipednav::planning::local
