#include <gtest/gtest.h>

#include "bipednav/common/error.hpp"
#include "bipednav/planning/local/local_planner.hpp"
#include "bipednav/planning/local/local_planner_factory.hpp"
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

// A robot 0.08 m short of the goal, facing it: inside the parameters' 0.1 m, so both planners
// report the goal reached; once the server tightens the tolerance to 0.05 m, neither does, and
// both drive on towards the goal.
TEST(LocalPlanners, ATightenedGoalToleranceKeepsTheRobotGoing) {
  LocalPlannerParams p;
  p.teb.xy_goal_tolerance_m = p.tracker.xy_goal_tolerance_m = 0.1;
  p.teb.xy_goal_release_m = p.tracker.xy_goal_release_m = 0.2;
  const auto map = test::empty_costmap(0.0, 0.0);
  const Path plan = test::straight_plan(-2.0, 0.0, 0.0, 0.0);
  for (const char* name : {"teb", "tracker"}) {
    auto planner = make_local_planner(name, p, nullptr);
    EXPECT_TRUE(planner->compute({-0.08, 0.0, 0.0}, {}, plan, map, 0.0).goal_reached) << name;
    planner = make_local_planner(name, p, nullptr);
    planner->set_xy_goal_tolerance(0.05);
    const auto r = planner->compute({-0.08, 0.0, 0.0}, {}, plan, map, 0.0);
    EXPECT_FALSE(r.goal_reached) << name;
    EXPECT_GT(r.cmd.linear_x, 0.0) << name;
  }
}

}  // namespace bipednav::planning::local
