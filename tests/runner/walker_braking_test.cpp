// A walker brakes from its last command, not from its lagging odometry
// (NavigatorParams::brake_from_last_command).
#include <gtest/gtest.h>

#include "bipednav/navigation/robot_loading.hpp"
#include "bipednav/runner/scenario_runner.hpp"
#include "test_data.hpp"

using namespace bipednav;

TEST(WalkerBraking, OnForWalkersOnly) {
  EXPECT_TRUE(navigation::navigator_params_for(navigation::load_robot("digit")).brake_from_last_command);
  EXPECT_FALSE(navigation::navigator_params_for(navigation::load_robot("turtlebot3")).brake_from_last_command);
}

// Seed 9: Digit heads for the person's lane while the person walks down it towards Digit's path.
// Braking from the measured velocity, the yield's stop took effect at a third of the deceleration
// limit: Digit kept 0.4 m/s for 1 s, stopped in the lane and was walked into at t = 24.3 s.
TEST(WalkerBraking, DigitStopsForThePersonCrossingItsPath) {
  runner::RunOptions o;
  o.robot = "digit";
  o.seed = 9;
  const runner::RunResult r =
      runner::run_scenario(sim::load_scenario(test::source_dir() / "scenarios" / "digit_lab_dynamic.yaml"), o);
  EXPECT_TRUE(r.success) << outcome_name(r.outcome.outcome) << " " << r.outcome.message;
  EXPECT_EQ(r.collisions, 0) << (r.first_collision ? r.first_collision->obstacle : "");
}
