// runner::path_departs: which replans get a figure panel (some pose of the new path farther than the
// limit from every pose of the old one).
#include <gtest/gtest.h>

#include <algorithm>

#include "bipednav/runner/scenario_runner.hpp"

using namespace bipednav;

namespace {

// A straight path along x from 0 to length_m, one pose per step_m, offset by y_m.
Path straight(double length_m, double step_m, double y_m = 0.0) {
  Path p;
  for (double x = 0.0; x <= length_m + 1e-9; x += step_m) p.poses.push_back({x, y_m, 0.0});
  return p;
}

}  // namespace

TEST(PathDeparts, EmptyPaths) {
  const Path some = straight(2.0, 0.05);
  EXPECT_FALSE(runner::path_departs(Path{}, Path{}));
  EXPECT_TRUE(runner::path_departs(Path{}, some));
  EXPECT_FALSE(runner::path_departs(some, Path{}));
}

TEST(PathDeparts, SameShiftedWithinTheLimitOrReversedPathsDoNotDepart) {
  const Path a = straight(5.0, 0.05);
  EXPECT_FALSE(runner::path_departs(a, a));
  EXPECT_FALSE(runner::path_departs(a, straight(5.0, 0.05, 0.45)));
  Path reversed = a;
  std::reverse(reversed.poses.begin(), reversed.poses.end());
  EXPECT_FALSE(runner::path_departs(a, reversed));
  // A shorter path along the old one, starting in its middle (the search wraps round the old path).
  Path tail;
  for (std::size_t i = 60; i < a.size(); ++i) tail.poses.push_back(a.poses[i]);
  EXPECT_FALSE(runner::path_departs(a, tail));
}

TEST(PathDeparts, ADetourOrALongerPathDeparts) {
  const Path a = straight(5.0, 0.05);
  EXPECT_TRUE(runner::path_departs(a, straight(5.0, 0.05, 0.55)));
  // One pose of a detour 0.6 m off the old path, the rest on it.
  Path detour = a;
  detour.poses[50].y = 0.6;
  EXPECT_TRUE(runner::path_departs(a, detour));
  // ... and 0.4 m off: not a departure.
  detour.poses[50].y = 0.4;
  EXPECT_FALSE(runner::path_departs(a, detour));
  // The new path goes 1 m further than the old one's end.
  EXPECT_TRUE(runner::path_departs(a, straight(6.0, 0.05)));
  EXPECT_FALSE(runner::path_departs(straight(6.0, 0.05), a));
  // The limit is a parameter.
  EXPECT_FALSE(runner::path_departs(a, straight(5.0, 0.05, 0.55), 0.6));
}
