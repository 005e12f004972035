// `run --params FILE`: the file overlays the robot's defaults, the single options win over it; a
// humanoid's file overlays the footstep navigator's.
#include <gtest/gtest.h>

#include "bipednav/navigation/navigator_params_yaml.hpp"
#include "bipednav/navigation/robot_loading.hpp"
#include "bipednav/runner/footstep_runner.hpp"
#include "bipednav/runner/scenario_runner.hpp"
#include "test_data.hpp"

using namespace bipednav;

TEST(RunParamsFile, OverlaysTheRobotsDefaultsAndTheOptionsWin) {
  BIPEDNAV_REQUIRE_DATA(file, "navigator_params/override.yaml");
  const RobotProfile robot = navigation::load_robot("digit");
  runner::RunOptions o;
  const navigation::NavigatorParams defaults = runner::navigator_params(robot, o);
  EXPECT_EQ(defaults.server.local_planner, "tracker");
  o.params_file = file;
  const navigation::NavigatorParams from_file = runner::navigator_params(robot, o);
  EXPECT_EQ(from_file.server.local_planner, "teb");
  EXPECT_TRUE(from_file.server.local.teb.optim.dynamic_obstacles);
  EXPECT_EQ(from_file.control_rate_hz, 20.0);
  EXPECT_EQ(from_file.server.local.teb.limits.velocity.max_vel_x_mps,
            defaults.server.local.teb.limits.velocity.max_vel_x_mps);
  o.local_planner = "tracker";  // --local-planner
  const navigation::NavigatorParams with_option = runner::navigator_params(robot, o);
  EXPECT_EQ(with_option.server.local_planner, "tracker");
  EXPECT_EQ(with_option.control_rate_hz, 20.0);
  o.params_file = file.parent_path() / "no_such_file.yaml";
  EXPECT_THROW(runner::navigator_params(robot, o), FileError);
}

// A humanoid's `run --params FILE`: the file overlays the footstep navigator's defaults.
TEST(RunParamsFile, OverlaysTheFootstepNavigatorsDefaults) {
  BIPEDNAV_REQUIRE_DATA(file, "navigator_params/footstep_override.yaml");
  const RobotProfile nao = navigation::load_robot("nao");
  const navigation::FootstepNavigatorParams defaults;
  EXPECT_EQ(navigation::navigator_params_yaml(runner::footstep_navigator_params(nao, {})),
            navigation::navigator_params_yaml(defaults));
  const navigation::FootstepNavigatorParams p = runner::footstep_navigator_params(nao, file);
  EXPECT_EQ(p.replan_deviation_m, 0.05);
  EXPECT_EQ(p.planner.search.initial_epsilon, 4.0);
  EXPECT_EQ(p.planner.search.target_epsilon, defaults.planner.search.target_epsilon);
  EXPECT_THROW(runner::footstep_navigator_params(nao, file.parent_path() / "no_such_file.yaml"), FileError);
}
