#include <gtest/gtest.h>

#include "bipednav/planning/local/plan_utils.hpp"
#include "bipednav/planning/local/tracker.hpp"
#include "local_test_utils.hpp"

namespace bipednav::planning::local {

TEST(PlanUtils, ClampCommandToAccelerationThenVelocity) {
  const CommandLimits lim{0.5, 0.2, 0.8, 0.5, 1.0};
  Twist t = clamp_command({1.0, 0.3, 2.0}, {0.0, 0.0, 0.0}, lim, 0.1);
  EXPECT_DOUBLE_EQ(t.linear_x, 0.05);
  EXPECT_DOUBLE_EQ(t.linear_y, 0.0);
  EXPECT_DOUBLE_EQ(t.angular_z, 0.1);
  t = clamp_command({-1.0, 0.0, 0.0}, {-0.19, 0.0, 0.0}, lim, 0.1);
  EXPECT_DOUBLE_EQ(t.linear_x, -0.2);
  t = clamp_command({NAN, 0.0, 0.0}, {}, lim, 0.1);
  EXPECT_TRUE(t.is_zero());
}

TEST(PlanUtils, LocalGoalIsTheLastPlanPoseInsideTheWindow) {
  const auto map = test::empty_costmap(0.0, 0.0, 4.0);  // window [-2, 2]^2
  const Path plan = test::straight_plan(0.0, 0.0, 5.0, 0.0);
  LocalGoal lg = select_local_goal(plan, {0, 0, 0}, map, 10.0, 0.2, 0.5);
  EXPECT_NEAR(lg.goal.x, 1.8, 1e-9);
  EXPECT_FALSE(lg.is_final);
  EXPECT_EQ(lg.via_points.size(), 3u);                              // 0.5, 1.0, 1.5
  lg = select_local_goal(plan, {0.5, 0.1, 0}, map, 1.0, 0.2, 0.5);  // lookahead-limited
  EXPECT_NEAR(lg.goal.x, 1.5, 1e-9);
  const Path shortp = test::straight_plan(0.0, 0.0, 1.0, 0.0, 0.1, 1.0);
  lg = select_local_goal(shortp, {0, 0, 0}, map, 3.0, 0.2, 0.5);
  EXPECT_TRUE(lg.is_final);
  EXPECT_DOUBLE_EQ(lg.goal.theta, 1.0);
}

TEST(PlanUtils, FeasibilityChecksLethalAndInscribedCells) {
  auto map = test::empty_costmap(0.0, 0.0, 4.0);
  test::add_disc(map, 1.0, 0.0, 0.1, 0.2);
  EXPECT_FALSE(poses_feasible({{0, 0, 0}, {2, 0, 0}}, map));     // crosses the obstacle
  EXPECT_FALSE(poses_feasible({{0, 0, 0}, {0.75, 0, 0}}, map));  // ends in inscribed space
  EXPECT_TRUE(poses_feasible({{0, 0, 0}, {2, 1, 0}}, map));
  EXPECT_TRUE(poses_feasible({{0.75, 0, 0}, {0.5, 0, 0}}, map));  // leaving inscribed space is fine
}

TEST(PlanUtils, OscillationDetector) {
  OscillationDetector det(10, 0.5, 0.8);
  for (int i = 0; i < 10; ++i) det.update({0.5, 0.0, 0.0});
  EXPECT_FALSE(det.oscillating());
  for (int i = 0; i < 10; ++i) det.update({0.0, 0.0, i % 2 == 0 ? 0.5 : -0.5});
  EXPECT_TRUE(det.oscillating());
  det.clear();
  EXPECT_FALSE(det.oscillating());
}

TEST(PlanUtils, ApproachGoalTurnsOnTheSpot) {
  const auto a = approach_goal({0, 0, 0}, {0.1, 0, 1.0}, 0.2, 0.2, 1.5, 0.8);
  EXPECT_TRUE(a.near);
  EXPECT_FALSE(a.reached);
  EXPECT_DOUBLE_EQ(a.cmd.linear_x, 0.0);
  EXPECT_DOUBLE_EQ(a.cmd.angular_z, 0.8);
  EXPECT_TRUE(approach_goal({0, 0, 0}, {0.1, 0, 0.1}, 0.2, 0.2, 1.5, 0.8).reached);
}

TEST(PathTracker, PurePursuitCurvature) {
  TrackerParams p;
  const Twist t = pure_pursuit_command({1.0, 0.0}, 5.0, p);
  EXPECT_DOUBLE_EQ(t.linear_x, p.max_vel_x_mps);
  EXPECT_DOUBLE_EQ(t.angular_z, 0.0);
  const Twist u = pure_pursuit_command({0.6, 0.2}, 5.0, p);  // kappa = 2 * 0.2 / 0.4 = 1
  EXPECT_NEAR(u.angular_z / u.linear_x, 1.0, 1e-12);
  const Twist w = pure_pursuit_command({-1.0, 0.1}, 5.0, p);  // behind: turn on the spot
  EXPECT_DOUBLE_EQ(w.linear_x, 0.0);
  EXPECT_GT(w.angular_z, 0.0);
}

TEST(PathTracker, ReachesGoalAndStopsBeforeObstacles) {
  PathTracker tracker(TrackerParams{});
  auto map = test::empty_costmap(1.5, 0.0);
  const Path plan = test::straight_plan(0.0, 0.0, 3.0, 0.5, 0.1, 0.0);
  const auto run = test::simulate(tracker, {0, 0, 0}, plan, map, 300);
  EXPECT_TRUE(run.reached) << run.final_pose.x << " " << run.final_pose.y;
  test::add_disc(map, 0.6, 0.0, 0.1);
  const auto r = tracker.compute({0, 0, 0}, {0.3, 0, 0}, test::straight_plan(0, 0, 3, 0), map, 0.0);
  EXPECT_EQ(r.result.outcome, Outcome::COLLISION);
  EXPECT_TRUE(r.cmd.is_zero());
}

}  // namespace bipednav::planning::local
