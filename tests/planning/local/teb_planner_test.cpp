#include "bipednav/planning/local/teb_planner.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

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

namespace bipednav::planning::local {
namespace {

void expect_within_limits(const std::vector<Twist>& cmds, const TebParams& p) {
  Twist prev;
  const double tol = 1e-9;
  for (const auto& c : cmds) {
    ASSERT_TRUE(c.is_finite());
    EXPECT_EQ(c.linear_y, 0.0);
    EXPECT_LE(c.linear_x, p.limits.velocity.max_vel_x_mps + tol);
    EXPECT_GE(c.linear_x, -p.limits.velocity.max_vel_x_backwards_mps - tol);
    EXPECT_LE(std::abs(c.angular_z), p.limits.velocity.max_vel_theta_radps + tol);
    EXPECT_LE(std::abs(c.linear_x - prev.linear_x), p.limits.velocity.acc_lim_x_mps2 * p.control_period_s + tol);
    EXPECT_LE(std::abs(c.angular_z - prev.angular_z),
              p.limits.velocity.acc_lim_theta_radps2 * p.control_period_s + tol);
    prev = c;
  }
}

}  // namespace

TEST(TebPlanner, KeepsSeparationInCorridorAndRespectsLimits) {
  TebParams params;
  TebPlanner planner(params);
  auto map = test::empty_costmap(1.5, 0.0);
  test::add_box(map, -1.0, 0.55, 4.0, 0.75, 0.15);
  test::add_box(map, -1.0, -0.75, 4.0, -0.55, 0.15);
  const Path plan = test::straight_plan(0.0, 0.0, 3.0, 0.0);
  const auto run = test::simulate(planner, {0.0, 0.05, 0.1}, plan, map, 250);
  EXPECT_TRUE(run.reached);
  for (const auto& p : run.poses) {
    EXPECT_LT(std::abs(p.y), 0.55 - 0.3) << "at x = " << p.x;
  }
  expect_within_limits(run.cmds, params);
}

TEST(TebPlanner, TakesTheFreeSideWhenOneSideIsBlocked) {
  TebParams params;
  TebPlanner planner(params);
  auto map = test::empty_costmap(1.5, 0.0);
  // An obstacle on the path whose left side (y > 0) is closed by a wall up to the window's edge.
  test::add_box(map, 1.4, -0.15, 1.6, 3.9, 0.2);
  const Path plan = test::straight_plan(0.0, 0.0, 3.0, 0.0);
  const auto run = test::simulate(planner, {0.0, 0.0, 0.0}, plan, map, 300);
  EXPECT_TRUE(run.reached) << "final " << run.final_pose.x << " " << run.final_pose.y;
  for (const auto& p : run.poses) {
    if (p.x > 1.2 && p.x < 1.8) {
      EXPECT_LT(p.y, -0.4);
    }
  }
  expect_within_limits(run.cmds, params);
}

TEST(TebPlanner, BacksOffTowardsAGoalBehindWhenTheWayAheadIsBlocked) {
  TebParams params;
  TebPlanner planner(params);
  auto map = test::empty_costmap(0.0, 0.0);
  test::add_box(map, 0.45, -3.0, 0.6, 3.0, 0.15);                        // wall right in front of the robot
  const Path plan = test::straight_plan(0.0, 0.0, -1.0, 0.0, 0.1, 0.0);  // goal 1 m behind, same heading
  const auto run = test::simulate(planner, {0.0, 0.0, 0.0}, plan, map, 300);
  EXPECT_TRUE(run.reached) << "final " << run.final_pose.x << " " << run.final_pose.y;
  const bool reversed =
      std::any_of(run.cmds.begin(), run.cmds.end(), [](const Twist& t) { return t.linear_x < -0.05; });
  EXPECT_TRUE(reversed);
  expect_within_limits(run.cmds, params);
}

TEST(TebPlanner, GoalBehindTheRobotIsReached) {
  TebParams params;
  TebPlanner planner(params);
  const auto map = test::empty_costmap(0.0, 0.0);
  const Path plan = test::straight_plan(0.0, 0.0, -2.0, 0.5, 0.1, M_PI);
  const auto first = planner.compute({0.0, 0.0, 0.0}, {}, plan, map, 0.0);
  EXPECT_EQ(first.result.outcome, Outcome::SUCCESS) << first.result.message;
  planner.reset();
  const auto run = test::simulate(planner, {0.0, 0.0, 0.0}, plan, map, 300);
  EXPECT_TRUE(run.reached) << "final " << run.final_pose.x << " " << run.final_pose.y;
  expect_within_limits(run.cmds, params);
}

TEST(TebPlanner, BadInputsGiveTypedOutcomes) {
  TebPlanner planner(TebParams{});
  const auto map = test::empty_costmap(0.0, 0.0);
  const Path plan = test::straight_plan(0.0, 0.0, 2.0, 0.0);
  auto r = planner.compute({0, 0, 0}, {}, Path{}, map, 0.0);
  EXPECT_EQ(r.result.outcome, Outcome::INVALID_PATH);
  EXPECT_TRUE(r.cmd.is_zero());
  r = planner.compute({NAN, 0, 0}, {}, plan, map, 0.0);
  EXPECT_EQ(r.result.outcome, Outcome::CTRL_TF_ERROR);
  EXPECT_TRUE(r.cmd.is_zero());
  r = planner.compute({0, 0, 0}, {NAN, 0, 0}, plan, map, 0.0);
  EXPECT_EQ(r.result.outcome, Outcome::CTRL_TF_ERROR);
  Path bad = plan;
  bad.poses[3].y = INFINITY;
  r = planner.compute({0, 0, 0}, {}, bad, map, 0.0);
  EXPECT_EQ(r.result.outcome, Outcome::INVALID_PATH);
  r = planner.compute({0, 0, 0}, {}, plan, mapping::Costmap2D{}, 0.0);
  EXPECT_EQ(r.result.outcome, Outcome::CTRL_MAP_ERROR);
  r = planner.compute({10, 0, 0}, {}, plan, map, 0.0);
  EXPECT_EQ(r.result.outcome, Outcome::CTRL_OUT_OF_MAP);
  // Still healthy afterwards.
  r = planner.compute({0, 0, 0}, {}, plan, map, 0.0);
  EXPECT_TRUE(r.result.ok());
}

TEST(TebPlanner, CollisionWhenTheRobotIsWalledIn) {
  TebPlanner planner(TebParams{});
  auto map = test::empty_costmap(0.0, 0.0);
  // A lethal ring around the robot: no trajectory can leave it.
  test::add_box(map, -0.5, 0.3, 0.5, 0.4, 0.0);
  test::add_box(map, -0.5, -0.4, 0.5, -0.3, 0.0);
  test::add_box(map, 0.3, -0.4, 0.4, 0.4, 0.0);
  test::add_box(map, -0.4, -0.4, -0.3, 0.4, 0.0);
  const Path plan = test::straight_plan(0.0, 0.0, 2.0, 0.0);
  const auto r = planner.compute({0, 0, 0}, {}, plan, map, 0.0);
  EXPECT_EQ(r.result.outcome, Outcome::BLOCKED_PATH);
  EXPECT_TRUE(r.cmd.is_zero());
}

TEST(TebPlanner, DeterministicForAFixedThreadCount) {
  auto map = test::empty_costmap(1.5, 0.0);
  test::add_disc(map, 1.2, 0.3, 0.1);
  test::add_disc(map, 2.0, -0.3, 0.1);
  test::add_disc(map, 1.6, 1.0, 0.1);
  const Path plan = test::straight_plan(0.0, 0.0, 3.0, 0.0);
  const auto run_with = [&](int threads) {
    TebParams p;
    p.homotopy.num_threads = threads;
    TebPlanner planner(p);
    return test::simulate(planner, {0, 0, 0}, plan, map, 40);
  };
  const auto a = run_with(3), b = run_with(3), c = run_with(1);
  ASSERT_EQ(a.cmds.size(), b.cmds.size());
  ASSERT_EQ(a.cmds.size(), c.cmds.size());
  for (std::size_t i = 0; i < a.cmds.size(); ++i) {
    EXPECT_EQ(a.cmds[i].linear_x, b.cmds[i].linear_x);
    EXPECT_EQ(a.cmds[i].angular_z, b.cmds[i].angular_z);
    EXPECT_EQ(a.cmds[i].linear_x, c.cmds[i].linear_x);  // every band is optimised independently
    EXPECT_EQ(a.cmds[i].angular_z, c.cmds[i].angular_z);
  }
}

}  // namespace bipednav::planning::local
