#include "bipednav/planning/local/interpolated_step.hpp"

#include <gtest/gtest.h>

namespace bipednav::planning::local {
namespace {

// The cubic through f(0) = 0, f'(0) = -3 and f(2) = 2, f'(2) = 9 is x^3 - 3x, minimised at x = 1;
// with the minimiser outside [lo, hi] the better end wins.
TEST(InterpolatedStep, MinimisesTheInterpolatingCubic) {
  const LineSearchSample s0{0.0, 0.0, -3.0, true};
  const LineSearchSample cur{2.0, 2.0, 9.0, true};
  EXPECT_NEAR(interpolated_step(s0, {}, cur, 0.002, 1.2), 1.0, 1e-12);
  EXPECT_NEAR(interpolated_step(s0, {}, cur, 0.002, 0.8), 0.8, 1e-12);
  // A previous sample of the same cubic (x = 1.5) leaves the minimiser where it is.
  const LineSearchSample prev{1.5, -1.125, 3.75, true};
  EXPECT_NEAR(interpolated_step(s0, prev, cur, 0.002, 1.2), 1.0, 1e-6);
  // A non-finite cost at the current step halves it.
  const LineSearchSample bad{0.8, 0.0, 0.0, false};
  EXPECT_DOUBLE_EQ(interpolated_step(s0, {}, bad, 0.001, 0.6), 0.4);
}

}  // namespace
}  // namespace bipednav::planning::local
