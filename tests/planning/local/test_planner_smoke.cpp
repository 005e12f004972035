#include <gtest/gtest.h>

#include "bipednav/common/error.hpp"
#include "bipednav/planning/local/local_planner.hpp"
#include "local_test_utils.hpp"

namespace bipednav::planning::local {

TEST(LocalPlannerFactory, MakesBothAndRejectsUnknown) {
  LocalPlannerParams p;
  EXPECT_EQ(make_local_planner("teb", p, nullptr)->name(), "teb");
  EXPECT_EQ(make_local_planner("tracker", p, nullptr)->name(), "tracker");
  EXPECT_THROW(make_local_planner("dwa", p, nullptr), ParamError);
}

TEST(TebPlannerSmoke, StraightEmptyPathGivesForwardCommand) {
  auto planner = make_local_planner("teb", {}, nullptr);
  const auto map = test::empty_costmap(0.0, 0.0);
  const Path plan = test::straight_plan(0.0, 0.0, 3.0, 0.0);
  const auto r = planner->compute({0.0, 0.0, 0.0}, {}, plan, map, 0.0);
  ASSERT_TRUE(r.result.ok()) << r.result.message;
  EXPECT_GT(r.cmd.linear_x, 0.0);
  EXPECT_GE(r.trajectory.size(), 3u);
}

}  // namespace bipednav::planning::local
