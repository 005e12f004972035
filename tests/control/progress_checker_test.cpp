#include "bipednav/control/progress_checker.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "bipednav/common/error.hpp"

namespace bipednav::control {
namespace {

TEST(ProgressChecker, StuckAfterAllowanceWithoutLeavingTheRadius) {
  ProgressCheckerParams p;
  p.required_movement_radius_m = 0.5;
  p.movement_time_allowance_s = 10.0;
  ProgressChecker c(p);
  // Swaying +-0.1 m around the start for 10 s is not progress but still allowed ...
  for (int i = 0; i <= 100; ++i) EXPECT_TRUE(c.check({0.1 * std::sin(i), 0.1 * std::cos(i), 0}, 0.1 * i));
  // ... past the allowance it is stuck.
  EXPECT_FALSE(c.check({0.05, 0, 0}, 10.1));
  EXPECT_NEAR(c.time_without_progress_s(10.1), 10.1, 1e-12);
}

TEST(ProgressChecker, MovingResetsTheWindow) {
  ProgressChecker c({0.5, 2.0});
  EXPECT_TRUE(c.check({0, 0, 0}, 0.0));
  EXPECT_TRUE(c.check({0.3, 0, 0}, 1.9));
  EXPECT_TRUE(c.check({0.5, 0, 0}, 2.5));  // 0.5 m from the reference: new reference at 2.5 s
  EXPECT_TRUE(c.check({0.6, 0, 0}, 4.5));
  EXPECT_FALSE(c.check({0.6, 0, 0}, 4.6));
  c.reset();
  EXPECT_TRUE(c.check({0.6, 0, 0}, 4.7));
}

TEST(ProgressChecker, RejectsBadInput) {
  EXPECT_THROW(ProgressChecker({0.0, 1.0}), ParamError);
  EXPECT_THROW(ProgressChecker({0.5, -1.0}), ParamError);
  ProgressChecker c;
  c.check({0, 0, 0}, 5.0);
  EXPECT_THROW(c.check({0, 0, 0}, 4.0), Error);
  EXPECT_THROW(c.check({std::nan(""), 0, 0}, 6.0), Error);
}

}  // namespace
}  // namespace bipednav::control
