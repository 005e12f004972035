#include "bipednav/common/wilson_interval.hpp"

#include <gtest/gtest.h>

namespace {

using bipednav::wilson_interval;

// Reference values of the 95 % Wilson score interval (z = 1.95996).
TEST(WilsonInterval, KnownValues) {
  const auto half = wilson_interval(5, 10);
  EXPECT_NEAR(half.lo, 0.2366, 1e-4);
  EXPECT_NEAR(half.hi, 0.7634, 1e-4);
  const auto none = wilson_interval(0, 10);
  EXPECT_DOUBLE_EQ(none.lo, 0.0);
  EXPECT_NEAR(none.hi, 0.2775, 1e-4);
  const auto all = wilson_interval(200, 200);
  EXPECT_NEAR(all.lo, 0.9812, 1e-4);
  EXPECT_DOUBLE_EQ(all.hi, 1.0);
  const auto nothing = wilson_interval(0, 0);
  EXPECT_DOUBLE_EQ(nothing.lo, 0.0);
  EXPECT_DOUBLE_EQ(nothing.hi, 1.0);
}

}  // namespace
