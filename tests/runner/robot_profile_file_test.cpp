// `--robot FILE.yaml`: the closed loop runs with a user's own robot profile, given as a file
// (loading the file: tests/navigation/robot_loading_test.cpp).
#include <gtest/gtest.h>

#include "bipednav/runner/scenario_runner.hpp"
#include "test_data.hpp"

using namespace bipednav;

// The four-camera walker starts hexagon_static's route.
TEST(RobotProfileFile, TheClosedLoopRunsWithAProfileFile) {
  BIPEDNAV_REQUIRE_DATA(file, "robots/four_camera_walker.yaml");
  sim::Scenario s = sim::load_scenario(test::source_dir() / "scenarios" / "hexagon_static.yaml");
  runner::RunOptions o;
  o.robot = file.string();
  o.time_limit_s = 8.0;
  const runner::RunResult r = runner::run_scenario(s, o);
  EXPECT_EQ(r.robot, "my_walker");
  EXPECT_EQ(r.collisions, 0);
  EXPECT_GT(r.path_length_m, 0.5);  // it walked towards the goal
}
