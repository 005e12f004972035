// What a navigation process loads before its first tick: the robot's profile (a name in config/ or
// the user's own file, `--robot FILE.yaml`) and the navigator's parameters in layers.
#include "bipednav/navigation/robot_loading.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "bipednav/common/error.hpp"
#include "test_data.hpp"

using namespace bipednav;

namespace {

std::filesystem::path write_profile(const std::string& file_name, const std::string& yaml) {
  const auto dir = std::filesystem::temp_directory_path() / "bipednav_robot_loading_test";
  std::filesystem::create_directories(dir);
  const auto path = dir / file_name;
  std::ofstream(path) << yaml;
  return path;
}

}  // namespace

TEST(RobotLoading, AFileIsLoadedAsTheUsersOwnRobotWithTheStructsDefaults) {
  BIPEDNAV_REQUIRE_DATA(file, "robots/four_camera_walker.yaml");
  const RobotProfile r = navigation::load_robot(file.string());
  EXPECT_EQ(r.name, "my_walker");
  EXPECT_EQ(r.kind, "walker");
  EXPECT_EQ(r.footprint_radius_m, 0.3);
  EXPECT_EQ(r.limits.max_vel_x_mps, 0.4);
  ASSERT_EQ(r.sensors.size(), 5u);
  ASSERT_NE(r.sensor("depth_left"), nullptr);
  EXPECT_EQ(r.sensor("depth_left")->yaw_rad, 1.571);
  EXPECT_EQ(r.sensor("depth_right")->y_m, -0.1);
  // No config/my_walker.params.yaml: the structs' defaults (not Digit's tuning) with its own limits.
  EXPECT_TRUE(navigation::robot_params_file(r).empty());
  const navigation::NavigatorParams p = navigation::navigator_params_for(r);
  EXPECT_EQ(p.server.local_planner, navigation::ServerParams{}.local_planner);
  EXPECT_FALSE(p.brake_from_last_command);
  EXPECT_EQ(p.server.local.tracker.limits.max_vel_x_mps, 0.4);
}

TEST(RobotLoading, ANameIsLookedUpInTheConfigDirectory) {
  EXPECT_EQ(navigation::load_robot("digit").name, "digit");
  EXPECT_EQ(navigation::load_robot("turtlebot3").kind, "diff_drive");
  EXPECT_EQ(navigation::robot_params_file(navigation::load_robot("digit")).filename(), "digit.params.yaml");
  EXPECT_THROW(navigation::load_robot("digit.params"), Error);  // a robot's tuning, not a profile
  try {
    navigation::load_robot("no_such_robot");
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("unknown robot 'no_such_robot'"), std::string::npos) << m;
    EXPECT_NE(m.find("digit, nao, turtlebot3"), std::string::npos) << m;  // the profiles there
  }
  EXPECT_THROW(navigation::load_robot(""), Error);
}

TEST(RobotLoading, AMissingOrInvalidFileIsAClearError) {
  try {
    navigation::load_robot("/no/such/dir/robot.yaml");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("robot profile file /no/such/dir/robot.yaml not found"), std::string::npos)
        << e.what();
  }
  const auto bad_kind = write_profile("hovercraft.yaml", "name: h\nkind: hovercraft\n");
  try {
    navigation::load_robot(bad_kind.string());
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("hovercraft.yaml"), std::string::npos) << m;
    EXPECT_NE(m.find("kind"), std::string::npos) << m;
  }
  const auto unknown_key = write_profile("typo.yaml", "name: t\nmax_vel_x: 0.3\n");
  EXPECT_THROW(navigation::load_robot(unknown_key.string()), Error);
}

// Defaults < the robot's tuning < the parameters file: the file changes only the fields it names.
TEST(RobotLoading, TheParametersFileOverlaysTheRobotsDefaults) {
  BIPEDNAV_REQUIRE_DATA(file, "navigator_params/override.yaml");
  const RobotProfile digit = navigation::load_robot("digit");
  const navigation::NavigatorParams defaults = navigation::navigator_params_for(digit);
  EXPECT_EQ(defaults.server.local_planner, "tracker");  // the walker's, over the struct's teb
  EXPECT_EQ(defaults.control_rate_hz, 10.0);
  const navigation::NavigatorParams from_file = navigation::navigator_params_for(digit, file);
  EXPECT_EQ(from_file.server.local_planner, "teb");
  EXPECT_EQ(from_file.control_rate_hz, 20.0);
  EXPECT_EQ(from_file.local_map.inflation_radius_m, 0.9);
  EXPECT_TRUE(from_file.server.local.teb.optim.dynamic_obstacles);
  EXPECT_EQ(from_file.brake_from_last_command, defaults.brake_from_last_command);  // not in the file
  EXPECT_EQ(from_file.server.local.teb.limits.velocity.max_vel_x_mps,
            defaults.server.local.teb.limits.velocity.max_vel_x_mps);
  EXPECT_THROW(navigation::navigator_params_for(digit, file.parent_path() / "no_such_file.yaml"), FileError);
}
