#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "bipednav/planning/local/teb_planner.hpp"
#include "local_test_utils.hpp"

namespace bipednav::planning::local {
namespace {

double min_dist_to(const std::vector<Pose2>& poses, double x, double y) {
  double d = 1e9;
  for (const auto& p : poses) d = std::min(d, std::hypot(p.x - x, p.y - y));
  return d;
}

}  // namespace

TEST(TebPlanner, ReachesGoalOnStraightEmptyPath) {
  TebPlanner planner(TebParams{});
  const auto map = test::empty_costmap(1.5, 0.0);
  const Path plan = test::straight_plan(0.0, 0.0, 3.0, 0.0);
  const auto run = test::simulate(planner, {0.0, 0.0, 0.0}, plan, map, 200);
  EXPECT_TRUE(run.reached) << "final " << run.final_pose.x << " " << run.final_pose.y;
  EXPECT_NEAR(run.final_pose.x, 3.0, 0.2);
  EXPECT_NEAR(run.final_pose.y, 0.0, 0.2);
  EXPECT_LT(run.steps, 150);
}

TEST(TebPlanner, KeepsSeparationAroundSingleObstacle) {
  TebParams params;
  TebPlanner planner(params);
  auto map = test::empty_costmap(1.5, 0.0);
  test::add_disc(map, 1.5, 0.05, 0.1, 0.2);
  const Path plan = test::straight_plan(0.0, 0.0, 3.2, 0.0);
  const auto run = test::simulate(planner, {0.0, 0.0, 0.0}, plan, map, 250);
  EXPECT_TRUE(run.reached) << "final " << run.final_pose.x << " " << run.final_pose.y;
  // Obstacle radius 0.1 + a tolerance for the cell discretisation and the soft constraint.
  EXPECT_GT(min_dist_to(run.poses, 1.5, 0.05), 0.1 + params.limits.min_obstacle_dist_m - 0.1);
}

}  // namespace bipednav::planning::local
