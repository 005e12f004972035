// `--robot FILE.yaml`: a user's own robot profile, given as a file instead of a name in config/.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "bipednav/navigation/navigator.hpp"
#include "bipednav/runner/scenario_runner.hpp"
#include "test_data.hpp"

using namespace bipednav;

namespace {

std::filesystem::path write_profile(const std::string& file_name, const std::string& yaml) {
  const auto dir = std::filesystem::temp_directory_path() / "bipednav_robot_profile_file_test";
  std::filesystem::create_directories(dir);
  const auto path = dir / file_name;
  std::ofstream(path) << yaml;
  return path;
}

// A walker of the user's own: Digit's body with depth cameras on all four sides.
const char* kFourCameraWalker = R"(name: my_walker
kind: walker
footprint_radius_m: 0.3
height_m: 1.5
max_vel_x_mps: 0.4
max_vel_x_backwards_mps: 0.2
max_vel_theta_radps: 0.5
acc_lim_x_mps2: 0.4
acc_lim_theta_radps2: 0.8
tracking_time_constant_s: 0.3
sway_amplitude_m: 0.02
step_frequency_hz: 2.0
sensors:
  - {name: lidar, type: vlp16, z_m: 1.4}
  - {name: depth_front, type: d430, x_m: 0.1, z_m: 0.95, pitch_rad: 0.785}
  - {name: depth_left, type: d430, y_m: 0.1, z_m: 0.95, pitch_rad: 0.785, yaw_rad: 1.571}
  - {name: depth_back, type: d430, x_m: -0.1, z_m: 0.95, pitch_rad: 0.785, yaw_rad: 3.142}
  - {name: depth_right, type: d430, y_m: -0.1, z_m: 0.95, pitch_rad: 0.785, yaw_rad: -1.571}
)";

}  // namespace

TEST(RobotProfileFile, AFileIsLoadedAsTheUsersOwnRobotWithItsKindsDefaults) {
  const auto file = write_profile("my_walker.yaml", kFourCameraWalker);
  const RobotProfile r = runner::load_robot(file.string());
  EXPECT_EQ(r.name, "my_walker");
  EXPECT_EQ(r.kind, "walker");
  EXPECT_EQ(r.footprint_radius_m, 0.3);
  EXPECT_EQ(r.max_vel_x_mps, 0.4);
  ASSERT_EQ(r.sensors.size(), 5u);
  ASSERT_NE(r.sensor("depth_left"), nullptr);
  EXPECT_EQ(r.sensor("depth_left")->yaw_rad, 1.571);
  EXPECT_EQ(r.sensor("depth_right")->y_m, -0.1);
  // A walker gets the walkers' defaults (the path tracker, braking from the last command), its own limits.
  const navigation::NavigatorParams p = runner::navigator_params(r, {});
  EXPECT_EQ(p.server.local_planner, "tracker");
  EXPECT_TRUE(p.brake_from_last_command);
  EXPECT_EQ(p.server.local.tracker.max_vel_x_mps, 0.4);
}

TEST(RobotProfileFile, ANameIsLookedUpInTheConfigDirectory) {
  EXPECT_EQ(runner::load_robot("digit").name, "digit");
  EXPECT_EQ(runner::load_robot("turtlebot3").kind, "diff_drive");
  try {
    runner::load_robot("no_such_robot");
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("unknown robot 'no_such_robot'"), std::string::npos) << m;
    EXPECT_NE(m.find("digit, nao, turtlebot3"), std::string::npos) << m;  // the profiles there
  }
  EXPECT_THROW(runner::load_robot(""), Error);
}

TEST(RobotProfileFile, AMissingOrInvalidFileIsAClearError) {
  try {
    runner::load_robot("/no/such/dir/robot.yaml");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("robot profile file /no/such/dir/robot.yaml not found"), std::string::npos)
        << e.what();
  }
  const auto bad_kind = write_profile("hovercraft.yaml", "name: h\nkind: hovercraft\n");
  try {
    runner::load_robot(bad_kind.string());
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("hovercraft.yaml"), std::string::npos) << m;
    EXPECT_NE(m.find("kind"), std::string::npos) << m;
  }
  const auto unknown_key = write_profile("typo.yaml", "name: t\nmax_vel_x: 0.3\n");
  EXPECT_THROW(runner::load_robot(unknown_key.string()), Error);
}

// The closed loop runs with a profile file: the four-camera walker starts hexagon_static's route.
TEST(RobotProfileFile, TheClosedLoopRunsWithAProfileFile) {
  const auto file = write_profile("my_walker_loop.yaml", kFourCameraWalker);
  sim::Scenario s = sim::load_scenario(test::source_dir() / "scenarios" / "hexagon_static.yaml");
  runner::RunOptions o;
  o.robot = file.string();
  o.time_limit_s = 8.0;
  const runner::RunResult r = runner::run_scenario(s, o);
  EXPECT_EQ(r.robot, "my_walker");
  EXPECT_EQ(r.collisions, 0);
  EXPECT_GT(r.path_length_m, 0.5);  // it walked towards the goal
}
