#include "bipednav/common/velocity_limits.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "bipednav/common/error.hpp"
#include "bipednav/common/rng.hpp"
#include "bipednav/common/robot_profile.hpp"
#include "test_limits.hpp"

namespace bipednav {
namespace {

VelocityLimits digit_like() { return test::forward_yaw_limits(0.5, 0.2, 0.6, 0.4, 1.0); }

TEST(VelocityLimits, ClampsVelocityAndAcceleration) {
  const VelocityLimits l = digit_like();
  const Twist out = limit_velocity({2.0, 0.3, -5.0}, {0.45, 0, -0.55}, 0.1, l);
  EXPECT_DOUBLE_EQ(out.linear_x, 0.49);   // 0.45 + 0.4 * 0.1, below the 0.5 cap
  EXPECT_DOUBLE_EQ(out.linear_y, 0.0);    // forward/yaw-only
  EXPECT_DOUBLE_EQ(out.angular_z, -0.6);  // capped
  EXPECT_DOUBLE_EQ(limit_velocity({-1.0, 0, 0}, {0, 0, 0}, 1.0, l).linear_x, -0.2);
  EXPECT_DOUBLE_EQ(limit_velocity({-1.0, 0, 0}, {-0.19, 0, 0}, 0.1, l).linear_x, -0.2);
  EXPECT_DOUBLE_EQ(limit_velocity({0.3, 0, 0.3}, {0.3, 0, 0.3}, 0.0, l).linear_x, 0.3);
  EXPECT_DOUBLE_EQ(limit_velocity({0.5, 0, 0}, {0.1, 0, 0}, 0.0, l).linear_x, 0.1);  // no time, no change
  const Twist from_rest = limit_velocity({1.0, 0.3, 2.0}, {}, 0.1, test::forward_yaw_limits(0.5, 0.2, 0.8, 0.5, 1.0));
  EXPECT_DOUBLE_EQ(from_rest.linear_x, 0.05);
  EXPECT_DOUBLE_EQ(from_rest.angular_z, 0.1);
}

// A measured velocity above a limit (a walker's sway, odometry noise): the command steps from it
// within the acceleration limit and the velocity limit then wins.
TEST(VelocityLimits, AMeasuredVelocityAboveTheLimitIsBroughtUnderIt) {
  const VelocityLimits l = digit_like();
  EXPECT_DOUBLE_EQ(limit_velocity({0.5, 0, 0}, {0.52, 0, 0}, 0.1, l).linear_x, 0.5);
  EXPECT_DOUBLE_EQ(limit_velocity({0.3, 0, 0}, {0.52, 0, 0}, 0.1, l).linear_x, 0.48);  // 0.52 - 0.04
  EXPECT_DOUBLE_EQ(limit_velocity({0.0, 0, 0}, {0.7, 0, 0}, 0.1, l).linear_x, 0.5);    // 0.66, capped
  EXPECT_DOUBLE_EQ(limit_velocity({0, 0, 0.6}, {0, 0, -0.8}, 0.1, l).angular_z, -0.6);
}

TEST(VelocityLimits, NonFiniteComponentsCountAsZero) {
  const VelocityLimits l = digit_like();
  const Twist braked = limit_velocity({std::nan(""), 0, 0.3}, {0.3, 0, 0.2}, 0.1, l);
  EXPECT_DOUBLE_EQ(braked.linear_x, 0.26);  // brakes at 0.4 m/s^2
  EXPECT_DOUBLE_EQ(braked.angular_z, 0.3);  // the finite component is kept
  const Twist from_nan = limit_velocity({0.5, 0, 0}, {std::nan(""), 0, 0}, 0.1, l);
  EXPECT_NEAR(from_nan.linear_x, 0.04, 1e-12);  // a NaN current velocity counts as rest
  EXPECT_THROW(limit_velocity({}, {}, -0.1, l), Error);
  EXPECT_THROW(limit_velocity({}, {}, std::nan(""), l), Error);
}

TEST(VelocityLimits, LateralMotionOnlyWhereAllowed) {
  VelocityLimits l = digit_like();
  EXPECT_EQ(limit_velocity({0, 0.3, 0}, {0, 0.1, 0}, 0.1, l).linear_y, 0.0);
  l.max_vel_y_mps = 0.2;
  l.acc_lim_y_mps2 = 0.5;
  EXPECT_DOUBLE_EQ(limit_velocity({0, 0.3, 0}, {0, 0.1, 0}, 0.1, l).linear_y, 0.15);
  EXPECT_DOUBLE_EQ(limit_velocity({0, 0.3, 0}, {0, 0.19, 0}, 0.1, l).linear_y, 0.2);
}

TEST(VelocityLimits, RandomCommandsNeverExceedLimits) {
  const VelocityLimits l = digit_like();
  Rng rng(7);
  Twist prev;
  const double dt = 0.05;
  for (int i = 0; i < 5000; ++i) {
    Twist cmd{rng.uniform(-3, 3), rng.uniform(-1, 1), rng.uniform(-4, 4)};
    if (rng.bernoulli(0.05)) cmd.linear_x = std::nan("");
    if (rng.bernoulli(0.05)) cmd.angular_z = std::numeric_limits<double>::infinity();
    const Twist out = limit_velocity(cmd, prev, dt, l);
    ASSERT_TRUE(out.is_finite());
    EXPECT_LE(out.linear_x, l.max_vel_x_mps + 1e-12);
    EXPECT_GE(out.linear_x, -l.max_vel_x_backwards_mps - 1e-12);
    EXPECT_EQ(out.linear_y, 0.0);
    EXPECT_LE(std::abs(out.angular_z), l.max_vel_theta_radps + 1e-12);
    EXPECT_LE(std::abs(out.linear_x - prev.linear_x), l.acc_lim_x_mps2 * dt + 1e-12);
    EXPECT_LE(std::abs(out.angular_z - prev.angular_z), l.acc_lim_theta_radps2 * dt + 1e-12);
    prev = out;
  }
}

TEST(VelocityLimits, ProfileIsForwardYawAndValidation) {
  // A robot profile embeds the limits with no lateral motion.
  EXPECT_EQ(RobotProfile{}.limits.max_vel_y_mps, 0.0);
  VelocityLimits bad;
  bad.acc_lim_x_mps2 = 0.0;
  EXPECT_THROW(bad.validate(), ParamError);
}

}  // namespace
}  // namespace bipednav
