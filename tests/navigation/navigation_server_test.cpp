// The navigation server's recovery actions: their commands ramp within the robot's acceleration
// limits, and each recovery is logged with its MBF outcome (150-158).
#include "bipednav/navigation/navigation_server.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "bipednav/common/error.hpp"
#include "bipednav/common/outcome.hpp"
#include "bipednav/mapping/global_costmap.hpp"
#include "bipednav/mapping/local_costmap.hpp"

namespace bipednav::navigation {
namespace {

// Digit's velocity and acceleration limits on a 0.3 m footprint.
RobotProfile walker() {
  RobotProfile r;
  r.footprint_radius_m = 0.3;
  r.limits.max_vel_x_mps = 0.5, r.limits.max_vel_x_backwards_mps = 0.25, r.limits.max_vel_theta_radps = 0.6;
  r.limits.acc_lim_x_mps2 = 0.5, r.limits.acc_lim_theta_radps2 = 1.0;
  return r;
}

struct NavigationServerRecovery : ::testing::Test {
  mapping::GlobalCostmap global{mapping::GridGeometry{200, 200, 0.05, -5.0, -5.0}};
  mapping::LocalCostmap local{};
  NavigationServer server{ServerParams{}, walker(), global, local, nullptr};

  void at(double t, const Pose2& pose = {}, const Twist& velocity = {}) { server.set_view({t, pose, velocity, 0.1}); }
  // Marks a wall of points at x = wall_x (map frame) in the local map around the robot at the origin.
  void wall_at(double wall_x) {
    mapping::Observation obs;
    obs.origin_map = Eigen::Vector3d(0.0, 0.0, 0.5);
    for (double y = -1.0; y <= 1.0; y += 0.02) obs.points_map.emplace_back(wall_x, y, 0.5);
    local.update(Pose2{}, {obs});
  }
};

TEST_F(NavigationServerRecovery, BackUpRampsToItsSpeedAtTheAccelerationLimit) {
  at(0.0);
  ActionStep s = server.back_up(0.3, 0.2, true);
  ASSERT_EQ(s.state, ActionStep::State::RUNNING);
  // 0.5 m/s^2 over 0.1 s from rest: -0.05 m/s, not the -0.2 m/s asked for.
  EXPECT_NEAR(server.command().linear_x, -0.05, 1e-12);
  at(0.1, {}, server.command());
  s = server.back_up(0.3, 0.2, false);
  EXPECT_NEAR(server.command().linear_x, -0.10, 1e-12);
  at(0.2, {}, Twist{-0.2, 0.0, 0.0});
  s = server.back_up(0.3, 0.2, false);
  EXPECT_NEAR(server.command().linear_x, -0.2, 1e-12);  // at speed: held there
  EXPECT_EQ(server.command().angular_z, 0.0);
}

TEST_F(NavigationServerRecovery, BackUpFromForwardMotionBrakesFirst) {
  at(0.0, {}, Twist{0.4, 0.0, 0.0});
  server.back_up(0.3, 0.2, true);
  EXPECT_NEAR(server.command().linear_x, 0.35, 1e-12);  // still forward, braking at 0.5 m/s^2
}

TEST_F(NavigationServerRecovery, RotateInPlaceRampsItsTurnRate) {
  at(0.0);
  ASSERT_EQ(server.rotate_in_place(-1.0, true).state, ActionStep::State::RUNNING);
  EXPECT_NEAR(server.command().angular_z, -0.1, 1e-12);  // 1 rad/s^2 over 0.1 s
  at(0.1, Pose2{0.0, 0.0, -0.01}, Twist{0.0, 0.0, -0.36});
  server.rotate_in_place(-1.0, false);
  EXPECT_NEAR(server.command().angular_z, -0.36, 1e-12);  // 0.6 of the 0.6 rad/s limit, reached
  EXPECT_EQ(server.command().linear_x, 0.0);
}

TEST_F(NavigationServerRecovery, RecoveriesAreLoggedWithTheirOutcomes) {
  at(1.0);
  EXPECT_TRUE(server.clear_costmaps().ok());
  EXPECT_TRUE(server.relax_constraints().ok());
  const Result again = server.relax_constraints();
  EXPECT_EQ(again.outcome, Outcome::RECOVERY_FAILURE);
  ASSERT_EQ(server.recovery_log().size(), 3u);
  EXPECT_EQ(server.recoveries(), 3u);
  const auto& log = server.recovery_log();
  EXPECT_EQ(log[0].name, "ClearCostmaps");
  EXPECT_EQ(log[0].result.outcome, Outcome::SUCCESS);
  EXPECT_EQ(log[1].name, "RelaxConstraints");
  EXPECT_EQ(log[2].result.outcome, Outcome::RECOVERY_FAILURE);
  EXPECT_EQ(code(log[2].result.outcome), 150);
  EXPECT_DOUBLE_EQ(log[2].start_s, 1.0);
  EXPECT_DOUBLE_EQ(log[2].end_s, 1.0);
}

TEST_F(NavigationServerRecovery, BackingIntoAnObstacleIsImpassable) {
  wall_at(-0.45);  // 0.05 m behind the probe 0.4 m behind the robot's centre
  at(2.0);
  const ActionStep s = server.back_up(0.3, 0.2, true);
  ASSERT_EQ(s.state, ActionStep::State::FAILED);
  EXPECT_EQ(s.result.outcome, Outcome::RECOVERY_IMPASSABLE);
  EXPECT_EQ(code(s.result.outcome), 158);
  EXPECT_TRUE(server.command().is_zero());
  ASSERT_EQ(server.recovery_log().size(), 1u);
  EXPECT_EQ(server.recovery_log()[0].name, "BackUp");
  EXPECT_EQ(server.recovery_log()[0].result.outcome, Outcome::RECOVERY_IMPASSABLE);
}

TEST_F(NavigationServerRecovery, BackingUpTooLongExceedsItsPatience) {
  at(0.0);
  server.back_up(0.3, 0.2, true);
  // The robot never moves: after 2 * 0.3 / 0.2 + 2 = 5 s the action gives up.
  at(5.05);
  const ActionStep s = server.back_up(0.3, 0.2, false);
  ASSERT_EQ(s.state, ActionStep::State::FAILED);
  EXPECT_EQ(s.result.outcome, Outcome::RECOVERY_PAT_EXCEEDED);
  EXPECT_DOUBLE_EQ(server.recovery_log().back().end_s, 5.05);
}

TEST_F(NavigationServerRecovery, AHaltedRecoveryEndsCanceledAndStopsTheRobot) {
  at(0.0);
  server.wait(2.0, true);
  at(0.5);
  ASSERT_EQ(server.wait(2.0, false).state, ActionStep::State::RUNNING);
  EXPECT_LT(server.recovery_log().back().end_s, 0.0);  // still running
  server.back_up(0.3, 0.2, true);                      // a recovery started over a running one supersedes it
  server.cancel_recovery();
  EXPECT_TRUE(server.command().is_zero());
  const auto& log = server.recovery_log();
  ASSERT_EQ(log.size(), 2u);
  EXPECT_EQ(log[0].result.outcome, Outcome::RECOVERY_CANCELED);
  EXPECT_DOUBLE_EQ(log[0].end_s, 0.5);
  EXPECT_EQ(log[1].result.outcome, Outcome::RECOVERY_CANCELED);
  EXPECT_EQ(code(log[1].result.outcome), 151);
  server.cancel_recovery();  // nothing running: no change
  EXPECT_EQ(server.recovery_log()[1].result.outcome, Outcome::RECOVERY_CANCELED);
}

TEST_F(NavigationServerRecovery, TheLogKeepsTheLatestRecoveries) {
  at(0.0);
  for (std::size_t i = 0; i < NavigationServer::kRecoveryLogSize + 10; ++i) {
    at(static_cast<double>(i));
    server.clear_costmaps();
  }
  EXPECT_EQ(server.recoveries(), NavigationServer::kRecoveryLogSize + 10);
  ASSERT_EQ(server.recovery_log().size(), NavigationServer::kRecoveryLogSize);
  EXPECT_DOUBLE_EQ(server.recovery_log().front().start_s, 10.0);
}

}  // namespace
}  // namespace bipednav::navigation

namespace bipednav::navigation {
namespace {

// A walker plans from its command's braking reference, but has stopped only when its body has: a
// reference at rest while the lagging body still turns does not reach the goal.
TEST_F(NavigationServerRecovery, TheGoalCheckWaitsForTheBodyToStop) {
  const Pose2 goal{0.0, 0.0, 0.05};  // inside the 0.2 m / 0.2 rad tolerances of the robot at the origin
  RobotView view{1.0, Pose2{}, Twist{}, 0.1};
  view.body_velocity = Twist{0.0, 0.0, 0.4};
  server.set_view(view);
  EXPECT_FALSE(server.goal_reached(goal));
  view.now_s = 1.1;
  view.body_velocity = Twist{};
  server.set_view(view);
  EXPECT_TRUE(server.goal_reached(goal));
  // Without a body velocity of its own the view's velocity is the body's.
  server.set_view({1.2, Pose2{}, Twist{0.0, 0.0, 0.4}, 0.1});
  EXPECT_FALSE(server.goal_reached(goal));
}

TEST(PlanClearance, AllowanceIsTwoSigmasInWholeCentimetres) {
  ServerParams p;
  EXPECT_NEAR(plan_clearance_allowance_m(p, 0.02), 0.04, 1e-12);
  EXPECT_NEAR(plan_clearance_allowance_m(p, 0.013), 0.03, 1e-12);  // 2.6 cm rounds up
  EXPECT_EQ(plan_clearance_allowance_m(p, 0.0), 0.0);
  ServerParams none;
  none.plan_clearance_sigmas = 0.0;
  EXPECT_EQ(plan_clearance_allowance_m(none, 0.3), 0.0);
  ServerParams bad;
  bad.plan_clearance_sigmas = -1.0;
  EXPECT_THROW(bad.validate(), ParamError);
  bad = {};
  bad.planning_recoveries_allowed = -1;
  EXPECT_THROW(bad.validate(), ParamError);
}

TEST(PlanClearance, PlanningRecoveriesAreBudgetedPerGoal) {
  mapping::GlobalCostmap global{mapping::GridGeometry{20, 20, 0.1, -1.0, -1.0}};
  mapping::LocalCostmap local{};
  ServerParams p;
  p.planning_recoveries_allowed = 2;
  NavigationServer server{p, RobotProfile{}, global, local, nullptr};
  EXPECT_TRUE(server.admit_planning_recovery());
  EXPECT_TRUE(server.admit_planning_recovery());
  EXPECT_FALSE(server.admit_planning_recovery());
  server.on_new_goal();
  EXPECT_TRUE(server.admit_planning_recovery());
}

}  // namespace
}  // namespace bipednav::navigation
