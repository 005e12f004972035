#include "bipednav/control/oscillation_checker.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "bipednav/common/error.hpp"

namespace bipednav::control {
namespace {

TEST(OscillationChecker, CountSignFlipsIgnoresDeadband) {
  EXPECT_EQ(count_sign_flips({0.1, -0.1, 0.1, -0.1}, 0.02), 3);
  EXPECT_EQ(count_sign_flips({0.1, 0.01, -0.01, 0.1}, 0.02), 0);
  EXPECT_EQ(count_sign_flips({0.1, 0.0, -0.1}, 0.0), 1);
  EXPECT_EQ(count_sign_flips({}, 0.02), 0);
}

TEST(OscillationChecker, ForwardBackwardInPlaceIsOscillation) {
  OscillationChecker c;  // 5 s window, 4 flips, 0.3 m
  bool osc = false;
  for (int i = 0; i < 20 && !osc; ++i) {
    const double v = (i / 2) % 2 == 0 ? 0.1 : -0.1;  // flips every 2 steps
    osc = c.check({v, 0, 0}, {0.01 * (i % 2), 0, 0}, 0.5 * i);
    if (i < 8) {
      EXPECT_FALSE(osc) << i;
    }
  }
  EXPECT_TRUE(osc);
  EXPECT_GE(c.last_flips(), 4);
}

TEST(OscillationChecker, FlipsWithNetProgressOrSlowFlipsAreNot) {
  OscillationChecker c;
  // Turning left/right (yaw flips) while walking forward 1 m per second.
  for (int i = 0; i < 40; ++i) EXPECT_FALSE(c.check({0.3, 0, i % 2 ? 0.2 : -0.2}, {0.1 * i, 0, 0}, 0.1 * i));
  // Setting off at 0.26 m/s with small steering corrections of either sign: the whole window's
  // progress (0.3 m) is due from the start, so this is oscillation until 0.3 m are covered (1.15 s).
  OscillationChecker whole;
  bool whole_oscillates = false;
  for (int i = 0; i < 60; ++i) {
    const bool osc = whole.check({0.26, 0, i % 2 ? 0.1 : -0.1}, {0.026 * i, 0, 0}, 0.1 * i);
    if (i >= 12) {
      EXPECT_FALSE(osc) << i;  // 0.312 m covered
    }
    whole_oscillates = osc || whole_oscillates;
  }
  EXPECT_TRUE(whole_oscillates);
  c.reset();
  // Flips every 2 s in place: never 4 within the 5 s window.
  for (int i = 0; i < 20; ++i) EXPECT_FALSE(c.check({i % 2 ? 0.1 : -0.1, 0, 0}, {0, 0, 0}, 2.0 * i));
}

TEST(OscillationChecker, YawOscillationAndNaNCommands) {
  OscillationChecker c;
  bool osc = false;
  for (int i = 0; i < 10; ++i) osc = c.check({std::nan(""), 0, i % 2 ? 0.5 : -0.5}, {0, 0, 0}, 0.2 * i);
  EXPECT_TRUE(osc);                                  // NaN linear speed counts as 0, the yaw flips 9 times
  EXPECT_THROW(c.check({}, {0, 0, 0}, 0.0), Error);  // time backwards
  EXPECT_THROW(c.check({}, {std::nan(""), 0, 0}, 5.0), Error);
  OscillationCheckerParams p;
  p.max_sign_flips = 0;
  EXPECT_THROW(OscillationChecker{p}, ParamError);
}

}  // namespace
}  // namespace bipednav::control
