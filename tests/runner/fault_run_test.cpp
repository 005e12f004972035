// End-to-end fault injection: each fault in a closed-loop run; the robot must stop or slow
// safely, never collide, and succeed once the fault is over.
#include <gtest/gtest.h>

#include "bipednav/runner/scenario_runner.hpp"
#include "test_data.hpp"

using namespace bipednav;

namespace {

runner::RunResult run_with(const std::string& name, const std::string& spec) {
  sim::Scenario s = sim::load_scenario(test::source_dir() / "scenarios" / (name + ".yaml"));
  s.faults.push_back(sim::parse_fault(spec));
  return runner::run_scenario(s, {});
}

void expect_safe_success(const runner::RunResult& r, const std::string& what) {
  EXPECT_TRUE(r.success) << what << ": " << outcome_name(r.outcome.outcome) << " " << r.outcome.message << " after "
                         << r.time_s << " s, goal error " << r.goal_error_m << " m";
  EXPECT_EQ(r.collisions, 0) << what << ": " << (r.first_collision ? r.first_collision->obstacle : "");
}

// The largest commanded speed while t is in [from_s, to_s].
double max_speed_between(const runner::RunResult& r, double from_s, double to_s) {
  double v = 0.0;
  for (const auto& s : r.trace)
    if (s.t_s >= from_s && s.t_s <= to_s) v = std::max({v, std::abs(s.cmd.linear_x), std::abs(s.cmd.angular_z)});
  return v;
}

TEST(FaultRun, LidarDropoutStopsTheRobotUntilSweepsReturn) {
  const auto r = run_with("hexagon_static", "lidar_dropout:6:3");
  expect_safe_success(r, "lidar dropout");
  EXPECT_GT(r.faults.sweeps_dropped, 25u);
  EXPECT_EQ(max_speed_between(r, 6.8, 9.0), 0.0);  // sensors silent after 0.5 s: stopped
}

// The LiDAR lost for good after the controller's recoveries have run: the run ends stopped, and the
// result names the silent sensor, not the recovered controller failure still on the blackboard.
TEST(FaultRun, LidarLostForGoodEndsStoppedWithTheSilentSensorAsTheOutcome) {
  sim::Scenario s = sim::load_scenario(test::source_dir() / "scenarios" / "hexagon_dynamic.yaml");
  s.faults.push_back(sim::parse_fault("lidar_dropout:25:60"));
  runner::RunOptions o;
  o.seed = 10;
  const runner::RunResult r = runner::run_scenario(s, o);
  EXPECT_GT(r.recoveries, 0);  // a controller failure was recovered before the LiDAR went
  EXPECT_FALSE(r.success);
  EXPECT_EQ(r.outcome.outcome, Outcome::CTRL_STOPPED) << outcome_name(r.outcome.outcome) << " " << r.outcome.message;
  EXPECT_NE(r.outcome.message.find("sensors went silent: lidar"), std::string::npos) << r.outcome.message;
  EXPECT_EQ(r.collisions, 0);
  ASSERT_FALSE(r.trace.empty());
  EXPECT_TRUE(r.trace.back().cmd.is_zero());
  EXPECT_EQ(max_speed_between(r, 26.0, r.time_s), 0.0);  // stopped from 0.5 s after the last sweep
}

TEST(FaultRun, DepthNanBurstStopsAWalkerThatLosesItsNearField) {
  const auto r = run_with("digit_lab_static", "depth_nan_burst:5:3:1.0");
  expect_safe_success(r, "depth NaN burst");
  EXPECT_GT(r.faults.depth_points_nan, 0u);
  EXPECT_EQ(max_speed_between(r, 5.8, 8.0), 0.0);
}

TEST(FaultRun, LocalizationJumpIsAbsorbedByLoam) {
  const auto r = run_with("hexagon_static", "localization_jump:8:1:0.8,-0.3,0.2");
  expect_safe_success(r, "localization jump");
  EXPECT_EQ(r.faults.odometry_jumps, 1u);
  EXPECT_LT(r.localization_error_m, 0.15);
}

TEST(FaultRun, OdometrySlipIsCorrectedByLoam) {
  const auto r = run_with("hexagon_static", "odometry_slip:4:8:0.3");
  expect_safe_success(r, "odometry slip");
  EXPECT_GT(r.faults.odometry_slipped, 100u);
  EXPECT_LT(r.localization_error_m, 0.15);
}

TEST(FaultRun, StaleTimestampsStopTheRobotUntilDataIsFreshAgain) {
  const auto r = run_with("hexagon_static", "stale_timestamps:6:3:1.0");
  expect_safe_success(r, "stale timestamps");
  EXPECT_GT(r.faults.messages_delayed, 100u);
  EXPECT_EQ(max_speed_between(r, 6.8, 9.0), 0.0);
}

// The link from the navigator to the walking controller cut for 3 s: the controller's watchdog
// stops the robot 0.5 s into the silence and the navigator's commands move it again afterwards.
TEST(FaultRun, CommandDropoutStopsTheRobotByTheWalkingControllersWatchdog) {
  const auto r = run_with("hexagon_static", "command_dropout:6:3");
  expect_safe_success(r, "command dropout");
  EXPECT_GE(r.faults.commands_dropped, 290u);  // 3 s of 10 ms steps
  EXPECT_EQ(r.watchdog_stops, 1u);
  EXPECT_NEAR(r.watchdog_stopped_s, 2.5, 0.05);
  EXPECT_GT(max_speed_between(r, 6.8, 9.0), 0.0);  // the navigator went on commanding
  // The robot stands still once it has braked (TurtleBot3: 0.26 m/s at 0.5 m/s^2 and more).
  const runner::TraceSample* a = nullptr;
  const runner::TraceSample* b = nullptr;
  for (const auto& s : r.trace) {
    if (!a && s.t_s >= 7.3) a = &s;
    if (s.t_s <= 8.95) b = &s;
  }
  ASSERT_TRUE(a && b && b->t_s > a->t_s + 1.0);
  EXPECT_LT(distance(a->true_pose, b->true_pose), 1e-6);
  EXPECT_LT(std::abs(a->true_pose.theta - b->true_pose.theta), 1e-6);
}

TEST(FaultRun, OutOfOrderTimestampsAreDropped) {
  const auto r = run_with("hexagon_static", "out_of_order_timestamps:5:4");
  expect_safe_success(r, "out-of-order timestamps");
  EXPECT_GT(r.faults.messages_reordered, 100u);
}

TEST(FaultRun, AFloodOfGoalChangesEndsAtTheLastGoal) {
  const auto r = run_with("hexagon_static", "goal_flood:2:3:30");
  expect_safe_success(r, "goal flood");
  EXPECT_GE(r.goals_given, 30u + 2u);
}

}  // namespace
