#include "bipednav/planning/local/plan_utils.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "bipednav/planning/local/tracker.hpp"
#include "local_test_utils.hpp"

namespace bipednav::planning::local {

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

TEST(PlanUtils, LethalClearanceIsTheDistanceToTheNearestLethalCellCentre) {
  auto map = test::empty_costmap(0.0, 0.0, 4.0);  // cells [-2 + 0.05 k, -2 + 0.05 (k + 1)]
  EXPECT_TRUE(std::isinf(lethal_clearance(map, 0.0, 0.0, 3.0)));
  map.set_cost(*map.geometry().world_to_cell(1.01, 0.01), mapping::kLethal);   // centre (1.025, 0.025)
  map.set_cost(*map.geometry().world_to_cell(-1.51, 0.01), mapping::kLethal);  // centre (-1.525, 0.025)
  Eigen::Vector2d nearest;
  EXPECT_NEAR(lethal_clearance(map, 0.0, 0.0, 3.0, &nearest), std::hypot(1.025, 0.025), 1e-12);
  EXPECT_NEAR(nearest.x(), 1.025, 1e-12);
  EXPECT_NEAR(lethal_clearance(map, -0.5, 0.0, 3.0), std::hypot(1.025, 0.025), 1e-12);  // the other one
  EXPECT_NEAR(lethal_clearance(map, 1.03, 0.02, 3.0), std::hypot(0.005, 0.005), 1e-12);
  EXPECT_TRUE(std::isinf(lethal_clearance(map, 0.0, 0.0, 1.0)));  // beyond max_m
}

TEST(PlanUtils, InInscribedSpaceOnlyPosesKeepingTheClearancePass) {
  auto map = test::empty_costmap(0.0, 0.0, 4.0);
  test::add_box(map, 0.5, -1.0, 1.5, 1.0, 0.38);
  // The robot at x = 0.25 is in inscribed space, 0.275 m from the nearest lethal cell centres.
  const Pose2 start{0.25, 0.0, 0.0};
  const std::vector<Pose2> closer{start, {0.4, 0.0, 0.0}};
  EXPECT_TRUE(poses_feasible(closer, map));  // the loophole: every inscribed cell costs the same
  EXPECT_FALSE(poses_keep_clearance(closer, map));
  EXPECT_FALSE(poses_keep_clearance({start, {0.25, 0.0, 0.0}, {0.27, 0.3, 0.0}}, map));  // in then out of reach
  EXPECT_TRUE(poses_keep_clearance({start, {0.1, 0.0, 0.0}}, map));                      // away
  EXPECT_TRUE(poses_keep_clearance({start, {0.25, 0.0, 1.5}, {0.25, 0.0, 3.0}}, map));   // turn on the spot
  EXPECT_TRUE(poses_keep_clearance({start, {0.2, 0.2, 0.0}, {-0.5, 0.4, 0.0}}, map));
  EXPECT_FALSE(poses_keep_clearance({start, {-0.2, 0.0, 0.0}, {0.6, 0.0, 0.0}}, map));  // into the box
  // Outside inscribed space it is poses_feasible.
  for (const auto& poses :
       {std::vector<Pose2>{{0.0, 0.0, 0.0}, {0.2, 0.0, 0.0}}, std::vector<Pose2>{{0.0, 0.0, 0.0}, {-0.5, 0.0, 0.0}}}) {
    EXPECT_EQ(poses_keep_clearance(poses, map), poses_feasible(poses, map));
  }
  EXPECT_FALSE(poses_keep_clearance({{0.0, 0.0, 0.0}, {0.2, 0.0, 0.0}}, map));
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

TEST(PlanUtils, ApproachGoalHoldsTheGoalUntilTheReleaseDistance) {
  bool holding = false;
  const Pose2 goal{0, 0, 1.0};
  const auto at = [&](double x) { return approach_goal({x, 0, 0}, goal, 0.1, 0.1, 1.5, 0.8, 0.2, &holding); };
  EXPECT_FALSE(at(0.15).near);  // not yet within 0.1 m
  EXPECT_FALSE(holding);
  EXPECT_TRUE(at(0.09).near);
  EXPECT_TRUE(holding);
  const auto drifted = at(0.15);  // drifted while turning: still turning on the spot
  EXPECT_TRUE(drifted.near);
  EXPECT_DOUBLE_EQ(drifted.cmd.linear_x, 0.0);
  EXPECT_GT(drifted.cmd.angular_z, 0.0);
  EXPECT_FALSE(at(0.21).near);  // beyond the release distance: back to following the path
  EXPECT_FALSE(holding);
  EXPECT_FALSE(at(0.15).near);
  // Without state (or with release <= tolerance) there is no hysteresis.
  EXPECT_FALSE(approach_goal({0.15, 0, 0}, goal, 0.1, 0.1, 1.5, 0.8).near);
  holding = true;
  EXPECT_FALSE(approach_goal({0.15, 0, 0}, goal, 0.1, 0.1, 1.5, 0.8, 0.1, &holding).near);
}

TEST(PathTracker, PurePursuitCurvature) {
  TrackerParams p;
  const Twist t = pure_pursuit_command({1.0, 0.0}, 5.0, p);
  EXPECT_DOUBLE_EQ(t.linear_x, p.limits.max_vel_x_mps);
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
  EXPECT_EQ(r.result.outcome, Outcome::BLOCKED_PATH);
  EXPECT_TRUE(r.cmd.is_zero());
}

namespace {

// The smallest lethal_clearance minus the start's along the robot's arc holding cmd for 1 s.
double clearance_change(const Pose2& start, const Twist& cmd, const mapping::Costmap2D& map) {
  const double c0 = lethal_clearance(map, start.x, start.y, 3.0);
  double worst = 0.0;
  Pose2 p = start;
  for (int i = 0; i < 100; ++i) {
    p = test::integrate(p, cmd, 0.01);
    worst = std::min(worst, lethal_clearance(map, p.x, p.y, 3.0) - c0);
  }
  return worst;
}

}  // namespace

// A robot whose estimate is already in inscribed space (0.275 m from the wall's lethal cells,
// inscribed radius 0.38 m) facing the wall, with a plan straight through it: an arc check that
// counts only lethal cells passes it; no command may bring the robot closer.
TEST(PathTracker, InInscribedSpaceFacingTheObstacleNoCommandClosesIn) {
  auto map = test::empty_costmap(0.0, 0.0);
  test::add_box(map, 0.5, -1.0, 1.5, 1.0, 0.38);
  const Pose2 start{0.25, 0.0, 0.0};
  const Path plan = test::straight_plan(0.25, 0.0, 3.0, 0.0);
  PathTracker tracker(TrackerParams{});
  // At rest: it backs away (straight back gains the most clearance).
  auto r = tracker.compute(start, {}, plan, map, 0.0);
  EXPECT_EQ(r.result.outcome, Outcome::SUCCESS);
  EXPECT_EQ(r.result.message, "leaving inscribed space");
  EXPECT_LT(r.cmd.linear_x, 0.0);
  EXPECT_DOUBLE_EQ(r.cmd.linear_x, -0.05);            // one period's deceleration limit
  EXPECT_LE(std::abs(r.cmd.angular_z), 0.1 + 1e-12);  // (turning a little while it backs)
  EXPECT_GE(clearance_change(start, r.cmd, map), 0.0);
  // Walking towards it at 0.3 m/s: every reachable command still closes in, so it stops.
  r = tracker.compute(start, {0.3, 0.0, 0.0}, plan, map, 0.0);
  EXPECT_EQ(r.result.outcome, Outcome::BLOCKED_PATH);
  EXPECT_TRUE(r.cmd.is_zero());
  // Turned 30 degrees off the wall: none of the commands closes in either.
  for (const double yaw : {-0.5, 0.5}) {
    const Pose2 s{0.25, 0.0, yaw};
    r = tracker.compute(s, {}, plan, map, 0.0);
    EXPECT_GE(clearance_change(s, r.cmd, map), 0.0) << yaw;
  }
}

TEST(PathTracker, InInscribedSpaceFacingAwayItWalksOn) {
  auto map = test::empty_costmap(0.0, 0.0);
  test::add_box(map, 0.5, -1.0, 1.5, 1.0, 0.38);
  PathTracker tracker(TrackerParams{});
  const Pose2 start{0.25, 0.0, M_PI};
  const auto r = tracker.compute(start, {0.2, 0.0, 0.0}, test::straight_plan(0.25, 0.0, -3.0, 0.0), map, 0.0);
  EXPECT_EQ(r.result.outcome, Outcome::SUCCESS);
  EXPECT_EQ(r.result.message, "ok");
  EXPECT_DOUBLE_EQ(r.cmd.linear_x, 0.25);
  EXPECT_GT(clearance_change(start, r.cmd, map), 0.0 - 1e-12);
}

// Closed loop from inside inscribed space, facing the wall, with a plan along it: the robot gets
// out (never closer to the wall while inside) and reaches the goal instead of freezing.
TEST(PathTracker, LeavesInscribedSpaceAndReachesTheGoal) {
  auto map = test::empty_costmap(0.0, -1.5);
  test::add_box(map, 0.5, -1.0, 1.5, 1.0, 0.38);
  PathTracker tracker(TrackerParams{});
  const Pose2 start{0.25, 0.0, 0.0};
  Path plan = test::straight_plan(0.25, 0.0, -0.3, -0.8);
  const Path rest = test::straight_plan(-0.3, -0.8, 1.0, -2.5);
  plan.poses.insert(plan.poses.end(), rest.poses.begin() + 1, rest.poses.end());
  const auto run = test::simulate(tracker, start, plan, map, 400);
  EXPECT_TRUE(run.reached) << run.final_pose.x << " " << run.final_pose.y;
  double prev = lethal_clearance(map, start.x, start.y, 3.0);
  for (const auto& p : run.poses) {
    const auto c = map.geometry().world_to_cell(p.x, p.y);
    ASSERT_TRUE(c);
    const double clearance = lethal_clearance(map, p.x, p.y, 3.0);
    EXPECT_NE(map.cost(*c), mapping::kLethal);
    if (map.cost(*c) >= mapping::kInscribed) {
      EXPECT_GE(clearance, prev - 1e-3) << p.x << " " << p.y;
    }
    prev = clearance;
  }
}

}  // namespace bipednav::planning::local
