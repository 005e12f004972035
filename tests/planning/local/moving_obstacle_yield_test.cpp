#include "bipednav/planning/local/moving_obstacle_yield.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "bipednav/planning/local/local_planner.hpp"
#include "bipednav/planning/local/local_planner_factory.hpp"
#include "bipednav/planning/local/moving_obstacles.hpp"
#include "local_test_utils.hpp"
#include "moving_obstacle_test_utils.hpp"
#include "test_limits.hpp"

namespace bipednav::planning::local {

namespace {

std::shared_ptr<MovingObstacleTracker> tracker_with(const Eigen::Vector2d& start, const Eigen::Vector2d& velocity,
                                                    double until_s) {
  auto t = std::make_shared<MovingObstacleTracker>(enabled_tracking());
  for (double s = 0.0; s <= until_s + 1e-9; s += 0.1) {
    std::vector<Eigen::Vector2d> pts;
    add_square(pts, start + velocity * s, 0.15, static_cast<int>(s * 10));
    t->update(pts, {0.0, 0.0}, s);
  }
  return t;
}

}  // namespace

TEST(MovingObstacles, TimeToCollisionHeadOnAndPassingBehind) {
  TrackedObstacle o;
  o.position = {2.0, 0.0};
  o.velocity = {-0.25, 0.0};
  o.radius_m = 0.1;
  DynamicAvoidanceParams p;
  p.robot_radius_m = 0.2;
  p.safety_margin_m = 0.1;
  p.prediction_growth_mps = 0.0;
  p.horizon_s = 4.0;
  // Closing at 0.5 m/s from 2 m: within reach (0.4 m) after 3.2 s.
  EXPECT_NEAR(time_to_collision({0, 0, 0}, {0.25, 0, 0}, {o}, 0.0, p), 3.2, 0.11);
  // Standing still: 6.4 s, beyond the horizon.
  EXPECT_TRUE(std::isinf(time_to_collision({0, 0, 0}, {}, {o}, 0.0, p)));
  // Moving away from us: never.
  o.velocity = {0.25, 0.0};
  EXPECT_TRUE(std::isinf(time_to_collision({0, 0, 0}, {0.2, 0, 0}, {o}, 0.0, p)));
}

TEST(MovingObstacles, HeadOnPredictedCollisionMakesTheTrackerStopOrBackOff) {
  const auto map = test::empty_costmap(0.0, 0.0, 8.0);
  const Path plan = test::straight_plan(0.0, 0.0, 3.5, 0.0);
  LocalPlannerParams params;
  params.avoidance.robot_radius_m = 0.3;
  // No moving obstacles: full speed ahead.
  auto free_tracker = make_local_planner("tracker", params, nullptr);
  const Twist cruise{0.5, 0.0, 0.0};
  const auto r0 = free_tracker->compute({0, 0, 0}, cruise, plan, map, 2.0);
  ASSERT_TRUE(r0.result.ok());
  EXPECT_GT(r0.cmd.linear_x, 0.4);
  // A box 1.7 m ahead walking at us at 0.3 m/s (seen from t = 0 to 2 s).
  const auto box = tracker_with({2.3, 0.0}, {-0.3, 0.0}, 2.0);
  ASSERT_EQ(box->moving(2.0).size(), 1u);
  for (const char* name : {"tracker", "teb"}) {
    SCOPED_TRACE(name);
    auto planner = make_local_planner(name, params, box.get());
    const auto r = planner->compute({0, 0, 0}, cruise, plan, map, 2.0);
    ASSERT_TRUE(r.result.ok()) << r.result.message;
    EXPECT_TRUE(planner->last_yield().modified);
    // Decelerating at the limit (0.5 m/s^2 over 0.1 s) towards a stop, a turn away or backing off.
    EXPECT_LT(r.cmd.linear_x, 0.5);
    EXPECT_LE(planner->last_yield().target.linear_x, 0.25);
    EXPECT_GT(planner->last_yield().ttc_s,
              time_to_collision({0, 0, 0}, cruise, box->moving(2.0), 2.0, params.avoidance));
  }
}

TEST(MovingObstacles, ObstacleThatPassesBeforeTheRobotArrivesChangesNothing) {
  const auto map = test::empty_costmap(0.0, 0.0, 8.0);
  const Path plan = test::straight_plan(0.0, 0.0, 3.5, 0.0);
  LocalPlannerParams params;
  params.avoidance.robot_radius_m = 0.3;
  // Crossing 3 m ahead, already past the robot's lane, moving away from it.
  const auto crossing = tracker_with({3.0, -1.0}, {0.0, -0.3}, 2.0);
  auto planner = make_local_planner("tracker", params, crossing.get());
  const auto r = planner->compute({0, 0, 0}, {0.5, 0.0, 0.0}, plan, map, 2.0);
  ASSERT_TRUE(r.result.ok());
  EXPECT_FALSE(planner->last_yield().modified);
  EXPECT_GT(r.cmd.linear_x, 0.4);
}

TEST(MovingObstacles, WhenEverythingCollidesTheCommandKeepingTheLargestGapWins) {
  // In a 0.9 m lane, a box already 0.5 m ahead and closing at 0.3 m/s: every candidate is within
  // reach at once; the yield must back off (the largest gap), not keep going or stop.
  auto map = test::empty_costmap(0.0, 0.0, 8.0);
  test::add_box(map, -3.0, 0.45, 3.0, 0.7);
  test::add_box(map, -3.0, -0.7, 3.0, -0.45);
  LocalPlannerParams params;
  params.avoidance.robot_radius_m = 0.3;
  const auto tracker = tracker_with({1.1, 0.0}, {-0.3, 0.0}, 2.0);
  const auto moving = tracker->moving(2.0);
  ASSERT_EQ(moving.size(), 1u);
  const VelocityLimits lim = bipednav::test::forward_yaw_limits(0.5, 0.25, 0.8, 0.5, 1.0);
  const auto y =
      yield_to_moving_obstacles({0.5, 0.0, 0.0}, {0, 0, 0}, {}, moving, map, lim, 0.1, 2.0, params.avoidance);
  ASSERT_TRUE(y.modified);
  EXPECT_LT(y.target.linear_x, 0.0) << y.target.linear_x << " " << y.target.angular_z;
  EXPECT_LT(y.cmd.linear_x, 0.0);
}

namespace {

// Where a command takes the robot from rest after t_s, within the acceleration limits (as the
// yield's rollouts: unicycle, velocity stepped towards the command every 0.1 s).
Pose2 roll_out(Pose2 pose, const Twist& target, const VelocityLimits& lim, double t_s) {
  Twist v;
  for (double t = 0.0; t < t_s - 1e-9; t += 0.1) {
    v.linear_x += std::clamp(target.linear_x - v.linear_x, -0.1 * lim.acc_lim_x_mps2, 0.1 * lim.acc_lim_x_mps2);
    v.angular_z +=
        std::clamp(target.angular_z - v.angular_z, -0.1 * lim.acc_lim_theta_radps2, 0.1 * lim.acc_lim_theta_radps2);
    pose = pose * Pose2{0.1 * v.linear_x, 0.0, 0.1 * v.angular_z};
  }
  return pose;
}

}  // namespace

TEST(MovingObstacles, InAMoversLaneWithNothingFreeTheLargestGapIsKept) {
  // Digit (radius 0.35 m, Digit's limits) standing in a 0.5 m cube's lane (x = 0), turned 0.6 rad
  // towards it, the cube 0.9 m away coming down the lane at 0.25 m/s (three_rooms/digit, cube_2
  // just after the robot crossed ahead of it): every candidate is run into. The one keeping the
  // largest gap backs off down the lane ahead of the cube, inside its corridor.
  const auto map = test::empty_costmap(0.0, 0.0, 8.0);
  const VelocityLimits lim = bipednav::test::forward_yaw_limits(0.5, 0.25, 0.6, 0.5, 1.0);
  TrackedObstacle cube;
  cube.position = {0.0, 0.9};
  cube.velocity = {0.0, -0.25};
  cube.radius_m = 0.35;
  DynamicAvoidanceParams p;
  p.robot_radius_m = 0.35;
  // The corridor's half-width at the end of the horizon.
  const double reach = p.robot_radius_m + cube.radius_m + p.safety_margin_m + p.prediction_growth_mps * p.horizon_s;
  const Pose2 pose{0.0, 0.0, 0.6};
  const Twist cmd{0.1, 0.0, -0.3};
  const auto gap = yield_to_moving_obstacles(cmd, pose, {}, {cube}, map, lim, 0.1, 0.0, p);
  ASSERT_TRUE(gap.modified);
  EXPECT_LT(gap.ttc_s, 0.5);  // nothing is free
  EXPECT_LT(gap.target.linear_x, 0.0);
  EXPECT_LT(std::abs(roll_out(pose, gap.target, lim, p.horizon_s).x), reach);
}

TEST(MovingObstacles, OfSeveralSafeCommandsTheClosestToThePlannersIsKept) {
  // A box crossing 1.2 m ahead from the right: slowing down or veering lets it pass; stopping
  // and backing off are safe too but further from the command.
  const auto map = test::empty_costmap(0.0, 0.0, 8.0);
  DynamicAvoidanceParams p;
  p.robot_radius_m = 0.2;
  const auto tracker = tracker_with({1.2, -1.6}, {0.0, 0.3}, 2.0);
  const auto moving = tracker->moving(2.0);
  ASSERT_EQ(moving.size(), 1u);
  const VelocityLimits lim = bipednav::test::forward_yaw_limits(0.5, 0.25, 0.8, 0.5, 1.0);
  const Twist cmd{0.5, 0.0, 0.0};
  const auto y = yield_to_moving_obstacles(cmd, {0, 0, 0}, cmd, moving, map, lim, 0.1, 2.0, p);
  ASSERT_TRUE(y.modified);
  EXPECT_TRUE(std::isinf(y.ttc_s));
  // Still moving forward (slower or veering away), neither stopping nor backing off.
  EXPECT_GT(y.target.linear_x, 0.0) << y.target.linear_x << " " << y.target.angular_z;
  EXPECT_FALSE(y.target.linear_x == cmd.linear_x && y.target.angular_z == cmd.angular_z);
}

TEST(MovingObstacles, BetweenTwoPostsInAMoversLaneHoldStepCandidatesStepAsideInsteadOfStanding) {
  // hexagon_dynamic/turtlebot3 seed 8 in miniature: the TurtleBot3 (radius 0.2 m, its limits)
  // stands in a box's lane (x = 0) between two posts (radius 0.15 m at x = +-0.4, 0.2 m inscribed
  // rings), facing one of them; the box comes down the lane at 0.25 m/s from 0.6 m. Every command
  // held for static_check_s (1.5 s) reaches a post's inscribed ring, so standing still was the
  // only candidate left; moving for a while and then braking is feasible and opens the gap.
  auto map = test::empty_costmap(0.0, 0.0, 8.0);
  test::add_disc(map, -0.4, 0.0, 0.15);
  test::add_disc(map, 0.4, 0.0, 0.15);
  const auto box_at = [](double y) {
    TrackedObstacle box;
    box.position = {0.0, y};
    box.velocity = {0.0, -0.25};
    box.radius_m = 0.1;
    return std::vector<TrackedObstacle>{box};
  };
  const auto moving = box_at(0.6);
  const VelocityLimits lim = bipednav::test::forward_yaw_limits(0.26, 0.26, 1.82, 2.5, 3.2);
  DynamicAvoidanceParams p;
  p.robot_radius_m = 0.2;
  const Twist cmd{0.26, 0.0, 0.0};
  ASSERT_EQ(p.hold_step_s, 0.0);
  const auto held = yield_to_moving_obstacles(cmd, {0, 0, 0}, {}, moving, map, lim, 0.1, 0.0, p);
  ASSERT_TRUE(held.modified);
  EXPECT_TRUE(held.target.is_zero()) << held.target.linear_x << " " << held.target.angular_z;
  p.hold_step_s = 0.25;
  const auto braked = yield_to_moving_obstacles(cmd, {0, 0, 0}, {}, moving, map, lim, 0.1, 0.0, p);
  ASSERT_TRUE(braked.modified);
  EXPECT_NE(braked.target.linear_x, 0.0) << braked.target.angular_z;
  EXPECT_NE(braked.cmd.linear_x, 0.0);
  EXPECT_TRUE(std::isfinite(braked.ttc_s));  // still run into: the lane is too narrow to clear it
  // In the open, with the box further up the lane, a held command is free, and the
  // held-then-braked ones are not considered.
  const auto open = test::empty_costmap(0.0, 0.0, 8.0);
  const auto far = box_at(1.2);
  p.hold_step_s = 0.0;
  const auto a = yield_to_moving_obstacles(cmd, {0, 0, 0}, {}, far, open, lim, 0.1, 0.0, p);
  p.hold_step_s = 0.25;
  const auto b = yield_to_moving_obstacles(cmd, {0, 0, 0}, {}, far, open, lim, 0.1, 0.0, p);
  EXPECT_FALSE(std::isfinite(a.ttc_s));
  EXPECT_EQ(a.target.linear_x, b.target.linear_x);
  EXPECT_EQ(a.target.angular_z, b.target.angular_z);
  EXPECT_EQ(a.ttc_s, b.ttc_s);
}

}  // namespace bipednav::planning::local
