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

TEST(GoalChecker, NonFiniteInputThrows) {
  GoalChecker c;
  EXPECT_THROW(c.reached({std::nan(""), 0, 0}, {0, 0, 0}), Error);
  EXPECT_THROW(c.reached({0, 0, 0}, {0, std::numeric_limits<double>::infinity(), 0}), Error);
}

}  // namespace
}  // namespace bipednav::control
