// End-to-end: the whole navigation loop in the simulator, one seed per scenario and robot.
#include <gtest/gtest.h>

#include "bipednav/runner/scenario_runner.hpp"
#include "test_data.hpp"

using namespace bipednav;

namespace {

sim::Scenario scenario(const std::string& name) {
  return sim::load_scenario(test::source_dir() / "scenarios" / (name + ".yaml"));
}

void expect_success(const std::string& name, const std::string& robot) {
  runner::RunOptions o;
  o.robot = robot;
  const runner::RunResult r = runner::run_scenario(scenario(name), o);
  EXPECT_TRUE(r.success) << name << "/" << robot << ": " << outcome_name(r.outcome.outcome) << " " << r.outcome.message
                         << " after " << r.time_s << " s, goal error " << r.goal_error_m << " m, collisions "
                         << r.collisions;
  EXPECT_EQ(r.collisions, 0) << (r.first_collision ? r.first_collision->obstacle : "");
  EXPECT_GT(r.min_clearance_m, 0.0);
}

}  // namespace

class ScenarioRun : public ::testing::TestWithParam<std::tuple<std::string, std::string>> {};

TEST_P(ScenarioRun, ReachesEveryGoalWithoutCollision) {
  expect_success(std::get<0>(GetParam()), std::get<1>(GetParam()));
}

// The pairs that pass today on their scenario seed. hexagon_dynamic/digit and turtlebot3_world/digit
// are infeasible (every route passes a 0.8 m gap between cylinders with 2 cm to spare per side
// beyond footprint and sway, less than the global planner's 0.04 m clearance allowance); they end with
// NO_PATH_FOUND (ScenarioRunOutcomes.DigitBehindTheCylinderGapEndsWithNoPathBeforeTheTimeLimit). One seed says little:
// over seeds 1-10 (`bench scenarios --seeds 10`) every passing pair scores 10/10 today, over fresh seeds 11-20 the
// TurtleBot3's 7/10 to 10/10 (README).
INSTANTIATE_TEST_SUITE_P(
    Thesis, ScenarioRun,
    ::testing::Values(std::tuple{"hexagon_static", "turtlebot3"}, std::tuple{"hexagon_static", "digit"},
                      std::tuple{"hexagon_dynamic", "turtlebot3"}, std::tuple{"digit_lab_static", "turtlebot3"},
                      std::tuple{"digit_lab_static", "digit"}, std::tuple{"digit_lab_dynamic", "turtlebot3"},
                      std::tuple{"digit_lab_dynamic", "digit"}, std::tuple{"turtlebot3_world", "turtlebot3"},
                      std::tuple{"three_rooms", "turtlebot3"}, std::tuple{"three_rooms", "digit"}),
    [](const auto& info) { return std::get<0>(info.param) + "_" + std::get<1>(info.param); });

TEST(ScenarioRunOutcomes, GoalInsideAnObstacleEndsInBlockedGoal) {
  sim::Scenario s = scenario("digit_lab_static");
  s.goals = {{0.0, {-0.5, 0.2, 0.0}}};  // the centre of obstacle_1
  s.time_limit_s = 60.0;
  const runner::RunResult r = runner::run_scenario(s, {});
  EXPECT_FALSE(r.success);
  // get_path's BLOCKED_GOAL (55) or exe_path's (109), whichever found it first.
  EXPECT_EQ(outcome_name(r.outcome.outcome), "BLOCKED_GOAL") << code(r.outcome.outcome) << " " << r.outcome.message;
  EXPECT_EQ(r.collisions, 0);
}

TEST(ScenarioRunOutcomes, UnreachableGoalEndsInNoPathFoundWithTheRobotStopped) {
  sim::Scenario s = scenario("digit_lab_static");
  s.goals = {{0.0, {6.2, 0.0, 0.0}}};  // outside the closed room (inside the global map's margin)
  s.time_limit_s = 120.0;
  const runner::RunResult r = runner::run_scenario(s, {});
  EXPECT_FALSE(r.success);
  EXPECT_EQ(r.outcome.outcome, Outcome::NO_PATH_FOUND) << outcome_name(r.outcome.outcome) << " " << r.outcome.message;
  EXPECT_EQ(r.collisions, 0);
  ASSERT_FALSE(r.trace.empty());
  EXPECT_TRUE(r.trace.back().cmd.is_zero());
}

// Digit's goal in hexagon_dynamic lies behind a 0.8 m gap between two cylinders that leaves it 0.019 m
// beyond footprint + sway (`bipednav route`), less than two position sigmas (0.04 m):
// the global planner sees the gap closed and the navigation ends, within the planning recoveries'
// budget, long before the time limit, without touching anything.
TEST(ScenarioRunOutcomes, DigitBehindTheCylinderGapEndsWithNoPathBeforeTheTimeLimit) {
  runner::RunOptions o;
  o.robot = "digit";
  o.seed = 1;
  const sim::Scenario s = scenario("hexagon_dynamic");
  const runner::RunResult r = runner::run_scenario(s, o);
  EXPECT_FALSE(r.success);
  EXPECT_TRUE(r.outcome.outcome == Outcome::NO_PATH_FOUND || r.outcome.outcome == Outcome::BLOCKED_GOAL)
      << outcome_name(r.outcome.outcome) << " " << r.outcome.message;
  EXPECT_LT(r.time_s, 60.0);
  EXPECT_EQ(r.collisions, 0) << (r.first_collision ? r.first_collision->obstacle : "");
  ASSERT_FALSE(r.trace.empty());
  EXPECT_TRUE(r.trace.back().cmd.is_zero());
}
