#include <gtest/gtest.h>

#include "bipednav/navigation/navigator.hpp"
#include "bipednav/planning/local/plan_utils.hpp"
#include "test_limits.hpp"

using namespace bipednav;
using navigation::acceleration_reference;

TEST(AccelerationReference, SlowingDownContinuesFromTheLastCommand) {
  // Measured 0.45 m/s (the walker lags), last command already down to 0.3 m/s.
  const Twist ref = acceleration_reference({0.45, 0.02, -0.4}, {0.3, 0.0, -0.2});
  EXPECT_DOUBLE_EQ(ref.linear_x, 0.3);
  EXPECT_DOUBLE_EQ(ref.angular_z, -0.2);
  EXPECT_DOUBLE_EQ(ref.linear_y, 0.02);
  // A stop then brakes one full period's change below the last command.
  const VelocityLimits lim = test::forward_yaw_limits(0.5, 0.25, 0.6, 0.5, 1.0);
  const Twist cmd = limit_velocity({}, ref, 0.1, lim);
  EXPECT_NEAR(cmd.linear_x, 0.25, 1e-12);
  EXPECT_NEAR(cmd.angular_z, -0.1, 1e-12);
}

TEST(AccelerationReference, SpeedingUpContinuesFromTheMeasuredVelocity) {
  const Twist ref = acceleration_reference({0.1, 0.0, 0.05}, {0.3, 0.0, 0.4});
  EXPECT_DOUBLE_EQ(ref.linear_x, 0.1);
  EXPECT_DOUBLE_EQ(ref.angular_z, 0.05);
  // Reversing from forward: the last command (nearer zero) is the reference.
  EXPECT_DOUBLE_EQ(acceleration_reference({0.2, 0.0, 0.0}, {-0.05, 0.0, 0.0}).linear_x, -0.05);
}
