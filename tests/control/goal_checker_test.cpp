#include "bipednav/control/goal_checker.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "bipednav/common/error.hpp"

namespace bipednav::control {
namespace {

TEST(GoalChecker, ThesisTolerances) {
  GoalChecker c;
  const Pose2 goal{2.0, 1.0, 0.5};
  EXPECT_TRUE(c.reached({2.0, 1.0, 0.5}, goal));
  EXPECT_TRUE(c.reached({2.19, 1.0, 0.69}, goal));
  EXPECT_FALSE(c.reached({2.21, 1.0, 0.5}, goal));  // 0.21 m away
  EXPECT_FALSE(c.reached({2.0, 1.0, 0.71}, goal));  // 0.21 rad off
  EXPECT_TRUE(c.reached({2.12, 1.16, 0.5}, goal));  // exactly 0.2 m (3-4-5)
}

TEST(GoalChecker, YawWrapsAroundPi) {
  GoalChecker c;
  EXPECT_TRUE(c.reached({0, 0, 3.1}, {0, 0, -3.1}));  // 0.083 rad apart across +-pi
  EXPECT_NEAR(goal_yaw_error_rad({0, 0, 3.1}, {0, 0, -3.1}), 2 * M_PI - 6.2, 1e-12);
  EXPECT_NEAR(goal_xy_error_m({1, 1, 0}, {4, 5, 0}), 5.0, 1e-12);
}

TEST(GoalChecker, ConfigurableAndYawOptional) {
  GoalCheckerParams p;
  p.xy_tolerance_m = 0.5;
  p.check_yaw = false;
  GoalChecker c(p);
  EXPECT_TRUE(c.reached({0.4, 0, 3.0}, {0, 0, 0}));
  p.xy_tolerance_m = -1.0;
  EXPECT_THROW(GoalChecker{p}, ParamError);
  p.xy_tolerance_m = 0.2;
  p.yaw_tolerance_rad = 4.0;
  EXPECT_THROW(GoalChecker{p}, ParamError);
}

TEST(GoalChecker, StatefulLatchesPositionUntilReset) {
  GoalCheckerParams p;
  p.stateful = true;
  GoalChecker c(p);
  const Pose2 goal{0, 0, 1.0};
  EXPECT_FALSE(c.reached({0.1, 0, 0.0}, goal));  // position ok, yaw not yet: latched
  EXPECT_TRUE(c.reached({0.25, 0, 1.0}, goal));  // drifted while turning: still reached
  c.reset();
  EXPECT_FALSE(c.reached({0.25, 0, 1.0}, goal));
}

TEST(GoalChecker, WaitsUntilTheRobotStopsInsideTheTolerance) {
  GoalChecker c;  // require_stopped by default
  const Pose2 goal{0, 0, 0};
  const Twist driving{0.26, 0.0, 0.0}, turning{0.0, 0.0, 0.5}, stopped{0.04, 0.2, 0.1};
  EXPECT_FALSE(c.reached({0.19, 0, 0}, goal, driving, 10.0));  // crossing the tolerance's edge
  EXPECT_FALSE(c.reached({0.12, 0, 0.05}, goal, turning, 10.2));
  EXPECT_TRUE(c.reached({0.1, 0, 0}, goal, stopped, 10.4));    // a walker's sway (linear_y) is no motion
  EXPECT_FALSE(c.reached({0.25, 0, 0}, goal, Twist{}, 10.6));  // stopped outside: not reached
}

TEST(GoalChecker, InsideForTheTimeOutCountsAsReachedWhileMoving) {
  GoalChecker c;
  const Pose2 goal{0, 0, 0};
  const Twist creeping{0.15, 0.0, 0.0};
  const double t_out = c.params().stopped_timeout_s;
  EXPECT_FALSE(c.reached({0.15, 0, 0}, goal, creeping, 5.0));
  EXPECT_FALSE(c.reached({0.15, 0, 0}, goal, creeping, 5.0 + t_out - 0.1));
  EXPECT_TRUE(c.reached({0.15, 0, 0}, goal, creeping, 5.0 + t_out));
  // Leaving the tolerance restarts the clock; so does reset().
  EXPECT_FALSE(c.reached({0.3, 0, 0}, goal, creeping, 9.0));
  EXPECT_FALSE(c.reached({0.15, 0, 0}, goal, creeping, 9.1));
  EXPECT_FALSE(c.reached({0.15, 0, 0}, goal, creeping, 9.1 + t_out - 0.1));
  c.reset();
  EXPECT_FALSE(c.reached({0.15, 0, 0}, goal, creeping, 9.1 + t_out + 0.1));
  // The yaw counts for "inside" too.
  EXPECT_FALSE(c.reached({0.1, 0, 0.5}, goal, creeping, 20.0));
  EXPECT_FALSE(c.reached({0.1, 0, 0.5}, goal, creeping, 20.0 + 2 * t_out));
}

TEST(GoalChecker, WithoutRequireStoppedTheToleranceAloneCounts) {
  GoalCheckerParams p;
  p.require_stopped = false;
  GoalChecker c(p);
  EXPECT_TRUE(c.reached({0.19, 0, 0}, {0, 0, 0}, Twist{0.26, 0.0, 1.0}, 0.0));
  p.trans_stopped_velocity_mps = 0.0;
  EXPECT_THROW(GoalChecker{p}, ParamError);
  p.trans_stopped_velocity_mps = 0.1;
  p.stopped_timeout_s = -1.0;
  EXPECT_THROW(GoalChecker{p}, ParamError);
}

TEST(GoalChecker, NonFiniteInputThrows) {
  GoalChecker c;
  EXPECT_THROW(c.reached({std::nan(""), 0, 0}, {0, 0, 0}), Error);
  EXPECT_THROW(c.reached({0, 0, 0}, {0, std::numeric_limits<double>::infinity(), 0}), Error);
  EXPECT_THROW(c.reached({0, 0, 0}, {0, 0, 0}, Twist{std::nan(""), 0, 0}, 0.0), Error);
}

}  // namespace
}  // namespace bipednav::control
