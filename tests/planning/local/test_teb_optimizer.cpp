#include <gtest/gtest.h>

#include "bipednav/planning/local/teb_optimizer.hpp"
#include "bipednav/planning/local/teb_planner.hpp"

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
  EXPECT_LT(cmd.linear_x, lim.max_vel_x_mps * 1.1);
}

}  // namespace bipednav::planning::local
