#include "bipednav/control/velocity_limiter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "bipednav/common/error.hpp"
#include "bipednav/common/rng.hpp"

namespace bipednav::control {
namespace {

VelocityLimits digit_like() {
  VelocityLimits l;
  l.max_vel_x_mps = 0.5;
  l.max_vel_x_backwards_mps = 0.2;
  l.max_vel_theta_radps = 0.6;
  l.acc_lim_x_mps2 = 0.4;
  l.acc_lim_theta_radps2 = 1.0;
  return l;
}

TEST(VelocityLimiter, ClampsVelocityAndAcceleration) {
  const VelocityLimits l = digit_like();
  const Twist out = limit_velocity({2.0, 0.3, -5.0}, {0.45, 0, -0.55}, 0.1, l);
  EXPECT_DOUBLE_EQ(out.linear_x, 0.49);   // 0.45 + 0.4 * 0.1, below the 0.5 cap
  EXPECT_DOUBLE_EQ(out.linear_y, 0.0);    // forward/yaw-only
  EXPECT_DOUBLE_EQ(out.angular_z, -0.6);  // capped
  const Twist back = limit_velocity({-1.0, 0, 0}, {0, 0, 0}, 1.0, l);
  EXPECT_DOUBLE_EQ(back.linear_x, -0.2);
  const Twist same = limit_velocity({0.3, 0, 0.3}, {0.3, 0, 0.3}, 0.0, l);
  EXPECT_DOUBLE_EQ(same.linear_x, 0.3);
  const Twist hold = limit_velocity({0.5, 0, 0}, {0.1, 0, 0}, 0.0, l);
  EXPECT_DOUBLE_EQ(hold.linear_x, 0.1);  // no time, no change
}

TEST(VelocityLimiter, RandomCommandsNeverExceedLimits) {
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

TEST(VelocityLimiter, NaNCommandBrakesToZero) {
  const VelocityLimits l = digit_like();
  VelocityLimiter lim(l);
  lim.apply({}, 0.0);
  Twist out;
  for (int i = 1; i <= 20; ++i) out = lim.apply({0.5, 0, 0.5}, 0.1 * i);
  EXPECT_DOUBLE_EQ(out.linear_x, 0.5);
  const Twist nan_cmd{std::nan(""), std::nan(""), std::nan("")};
  out = lim.apply(nan_cmd, 2.1);
  EXPECT_NEAR(out.linear_x, 0.46, 1e-12);  // braking at 0.4 m/s^2
  for (int i = 22; i <= 40; ++i) out = lim.apply(nan_cmd, 0.1 * i);
  EXPECT_TRUE(out.is_zero());
  // A NaN previous command counts as rest.
  const Twist from_nan = limit_velocity({0.5, 0, 0}, nan_cmd, 0.1, l);
  EXPECT_NEAR(from_nan.linear_x, 0.04, 1e-12);
}

TEST(VelocityLimiter, StatefulFirstCallStartsFromRestAndRejectsBadTime) {
  VelocityLimiter lim(digit_like());
  EXPECT_TRUE(lim.apply({0.5, 0, 0}, 3.0).is_zero());
  EXPECT_NEAR(lim.apply({0.5, 0, 0}, 3.5).linear_x, 0.2, 1e-12);
  EXPECT_THROW(lim.apply({}, 3.0), Error);
  EXPECT_THROW(limit_velocity({}, {}, -0.1, digit_like()), Error);
  EXPECT_THROW(limit_velocity({}, {}, std::nan(""), digit_like()), Error);
}

TEST(VelocityLimiter, FromProfileAndValidation) {
  RobotProfile digit;
  digit.max_vel_x_mps = 0.4;
  digit.max_vel_theta_radps = 0.5;
  const VelocityLimits l = VelocityLimits::from_profile(digit);
  EXPECT_EQ(l.max_vel_x_mps, 0.4);
  EXPECT_EQ(l.max_vel_y_mps, 0.0);
  EXPECT_EQ(l.acc_lim_theta_radps2, digit.acc_lim_theta_radps2);
  VelocityLimits bad;
  bad.acc_lim_x_mps2 = 0.0;
  EXPECT_THROW(bad.validate(), ParamError);
  bad = {};
  bad.max_vel_x_mps = std::nan("");
  EXPECT_THROW(VelocityLimiter{bad}, ParamError);
}

}  // namespace
}  // namespace bipednav::control
