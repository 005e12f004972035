// The navigation parameters file: `bipednav params` dump, read back, overrides and errors.
#include "bipednav/navigation/navigator_params_yaml.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <sstream>
#include <vector>

#include "bipednav/io/robot_profile_yaml.hpp"
#include "bipednav/navigation/robot_loading.hpp"
#include "test_data.hpp"

using namespace bipednav;
using navigation::FootstepNavigatorParams;
using navigation::NavigatorParams;

namespace {

RobotProfile robot_named(const std::string& name) {
  return io::load_robot_profile(std::filesystem::path(navigation::config_dir()) / (name + ".yaml"));
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// The lines of dump `after` that differ from dump `before` (same layout, so line by line).
std::set<std::string> changed_lines(const std::string& before, const std::string& after) {
  const auto a = lines_of(before), b = lines_of(after);
  EXPECT_EQ(a.size(), b.size());
  std::set<std::string> out;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i)
    if (a[i] != b[i]) out.insert(b[i]);
  return out;
}

// read_navigator_params on YAML text (a file called `name`) onto `p`; the error message when it
// throws `E` ("" when it did not).
template <class E, class Params>
std::string error_reading(const std::string& yaml, Params p, const std::string& name) {
  try {
    io::ParamReader r = io::ParamReader::from_string(yaml, name);
    navigation::read_navigator_params(r, p);
  } catch (const E& e) {
    return e.what();
  }
  return "";
}

// Onto TurtleBot3's navigator defaults.
template <class E>
std::string error_of(const std::string& yaml) {
  return error_reading<E>(yaml, navigation::navigator_params_for(robot_named("turtlebot3")), "nav_params.yaml");
}

// Onto the footstep navigator's defaults.
std::string footstep_error_of(const std::string& yaml) {
  return error_reading<FileError>(yaml, FootstepNavigatorParams{}, "nao_params.yaml");
}

}  // namespace

// The dump of one robot's parameters, read onto the other robot's defaults, gives back every value:
// the robot-dependent fields (radii, limits, planner, braking, LOAM's prior) included.
TEST(NavigatorParamsYaml, DumpReadBackGivesTheSameValuesForBothRobots) {
  const std::vector<std::string> robots{"turtlebot3", "digit"};
  for (std::size_t i = 0; i < robots.size(); ++i) {
    const NavigatorParams want = navigation::navigator_params_for(robot_named(robots[i]));
    const std::string text = navigation::navigator_params_yaml(want);
    NavigatorParams got = navigation::navigator_params_for(robot_named(robots[1 - i]));
    ASSERT_NE(navigation::navigator_params_yaml(got), text) << "the two robots' defaults differ";
    io::ParamReader r = io::ParamReader::from_string(text, robots[i] + ".yaml");
    navigation::read_navigator_params(r, got);
    EXPECT_EQ(navigation::navigator_params_yaml(got), text) << robots[i];
    EXPECT_EQ(got.local_map.inscribed_radius_m, want.local_map.inscribed_radius_m);
    EXPECT_EQ(got.local_map.inflation_radius_m, want.local_map.inflation_radius_m);
    EXPECT_EQ(got.local_map.height_aware_clearing, want.local_map.height_aware_clearing);
    EXPECT_EQ(got.local_map.mark_decay_s, want.local_map.mark_decay_s);
    EXPECT_EQ(got.global_map.inflation_radius_m, want.global_map.inflation_radius_m);
    EXPECT_EQ(got.perception.obstacle_height_margin_m, want.perception.obstacle_height_margin_m);
    EXPECT_EQ(got.perception.depth_voxel.leaf_size_m, want.perception.depth_voxel.leaf_size_m);
    EXPECT_EQ(got.perception.prior_ground, want.perception.prior_ground);
    EXPECT_EQ(got.localization.max_odometry_speed_mps, want.localization.max_odometry_speed_mps);
    EXPECT_EQ(got.localization.loam.reference_from_prior_change, want.localization.loam.reference_from_prior_change);
    EXPECT_EQ(got.server.local.teb.limits.velocity.max_vel_x_mps, want.server.local.teb.limits.velocity.max_vel_x_mps);
    EXPECT_EQ(got.server.local.teb.limits.min_obstacle_dist_m, want.server.local.teb.limits.min_obstacle_dist_m);
    EXPECT_EQ(got.server.local.tracker.limits.max_vel_theta_radps,
              want.server.local.tracker.limits.max_vel_theta_radps);
    EXPECT_EQ(got.server.local.avoidance.robot_radius_m, want.server.local.avoidance.robot_radius_m);
    EXPECT_EQ(got.server.progress.movement_time_allowance_s, want.server.progress.movement_time_allowance_s);
    EXPECT_EQ(got.server.local_planner, want.server.local_planner);
    EXPECT_EQ(got.brake_from_last_command, want.brake_from_last_command);
    EXPECT_EQ(got.behavior_tree, want.behavior_tree);
  }
}

// tests/data/navigator_params/override.yaml names six fields: exactly those six lines of the dump change.
TEST(NavigatorParamsYaml, AFileChangesExactlyTheFieldsItNames) {
  BIPEDNAV_REQUIRE_DATA(file, "navigator_params/override.yaml");
  const NavigatorParams before = navigation::navigator_params_for(robot_named("digit"));
  NavigatorParams p = before;
  navigation::apply_navigator_params_file(file, p);
  EXPECT_EQ(p.control_rate_hz, 20.0);
  EXPECT_EQ(p.local_map.inflation_radius_m, 0.9);
  EXPECT_EQ(p.perception.depth_voxel.leaf_size_m, Eigen::Vector3d(0.03, 0.03, 0.04));
  EXPECT_FALSE(p.moving_obstacles.coast_in_blind_zone);
  EXPECT_EQ(p.server.local_planner, "teb");  // Digit's default is the tracker
  EXPECT_TRUE(p.server.local.teb.optim.dynamic_obstacles);

  const std::set<std::string> changed =
      changed_lines(navigation::navigator_params_yaml(before), navigation::navigator_params_yaml(p));
  const std::set<std::string> expected{
      "control_rate_hz: 20.0",        "  inflation_radius_m: 0.9", "    leaf_size_m: [0.03, 0.03, 0.04]",
      "  coast_in_blind_zone: false", "  local_planner: teb",      "        dynamic_obstacles: true"};
  EXPECT_EQ(changed, expected);
}

TEST(NavigatorParamsYaml, AnUnknownKeyNamesTheFileAndTheFieldPath) {
  const std::string msg =
      error_of<FileError>("server:\n  local:\n    teb:\n      optim:\n        dynamic_obstacle: true\n");
  EXPECT_NE(msg.find("nav_params.yaml"), std::string::npos) << msg;
  EXPECT_NE(msg.find("server.local.teb.optim.dynamic_obstacle"), std::string::npos) << msg;
  EXPECT_NE(msg.find("unknown parameter"), std::string::npos) << msg;
  const std::string top = error_of<FileError>("control_rate: 20.0\n");
  EXPECT_NE(top.find("nav_params.yaml:control_rate: unknown parameter"), std::string::npos) << top;
  // Fields left out of the file format are unknown keys too.
  EXPECT_NE(
      error_of<FileError>("localization: {loam: {output_deskewed: true}}").find("localization.loam.output_deskewed"),
      std::string::npos);
}

TEST(NavigatorParamsYaml, AWrongTypeNamesTheFieldAndTheExpectedType) {
  const std::string msg = error_of<FileError>("local_map:\n  inflation_radius_m: wide\n");
  EXPECT_NE(msg.find("nav_params.yaml:line 2: local_map.inflation_radius_m: expected a value of type number"),
            std::string::npos)
      << msg;
  EXPECT_NE(error_of<FileError>("moving_obstacles: {enabled: 3}")
                .find("moving_obstacles.enabled: expected a value of type bool"),
            std::string::npos);
  EXPECT_NE(error_of<FileError>("server: {local: {teb: {optim: {no_inner_iterations: 2.5}}}}")
                .find("server.local.teb.optim.no_inner_iterations: expected a value of type integer"),
            std::string::npos);
  EXPECT_NE(error_of<FileError>("server: {goal: 0.3}").find("server.goal: expected a mapping"), std::string::npos);
  EXPECT_NE(error_of<FileError>("perception: {prior_ground: [0, 0, 1]}")
                .find("perception.prior_ground: expected a list of 4 numbers"),
            std::string::npos);
}

// Values of the right type but out of range: validate() after the overlay names the field, the
// error the file.
TEST(NavigatorParamsYaml, ValuesOutOfRangeAreRejectedByValidate) {
  const std::string msg = error_of<FileError>("local_map: {inflation_radius_m: -1.0}");
  EXPECT_NE(msg.find("nav_params.yaml: invalid parameter 'inflation_radius_m'"), std::string::npos) << msg;
  EXPECT_NE(error_of<FileError>("control_rate_hz: .nan").find("invalid parameter 'control_rate_hz'"),
            std::string::npos);
  EXPECT_NE(error_of<FileError>("server: {local_planner: dwa}").find("invalid parameter 'local_planner'"),
            std::string::npos);
  EXPECT_NE(error_of<FileError>("localization: {method: gps}").find("invalid parameter 'localization.method'"),
            std::string::npos);
  EXPECT_EQ(error_of<Error>("control_rate_hz: 20\n"), "");  // an integer is a number
}

// The footstep navigator (a humanoid's `bipednav params` / `run --params`).

// The dump of the defaults, read onto parameters that differ in every component, gives back every
// value (the navigator's scalars, planner with search, fusion, odometry with gicp).
TEST(FootstepNavigatorParamsYaml, DumpReadBackGivesTheSameValues) {
  const FootstepNavigatorParams want;
  const std::string text = navigation::navigator_params_yaml(want);
  FootstepNavigatorParams got;
  got.gicp_correction = false;
  got.max_plans = 7;
  got.max_recovery_steps = 0;
  got.obstacle_step_m = 0.05;
  got.planner.robot = "digit";
  got.planner.theta_bins = 16;
  got.planner.search.initial_epsilon = 8.0;
  got.planner.search.max_expansions = 1000;
  got.fusion.variance_per_m2 = 2e-4;
  got.odometry.gicp.max_correspondence_m = 1.0;
  got.odometry.min_points = 80;
  ASSERT_NE(navigation::navigator_params_yaml(got), text);
  io::ParamReader r = io::ParamReader::from_string(text, "nao.yaml");
  navigation::read_navigator_params(r, got);
  EXPECT_EQ(navigation::navigator_params_yaml(got), text);
  EXPECT_TRUE(got.gicp_correction);
  EXPECT_EQ(got.max_plans, want.max_plans);
  EXPECT_EQ(got.max_recovery_steps, want.max_recovery_steps);
  EXPECT_EQ(got.obstacle_step_m, want.obstacle_step_m);
  EXPECT_EQ(got.planner.robot, "nao");
  EXPECT_EQ(got.planner.theta_bins, want.planner.theta_bins);
  EXPECT_EQ(got.planner.search.initial_epsilon, 3.0);  // default_planner(), not AraStarParams' 8
  EXPECT_EQ(got.planner.search.max_expansions, want.planner.search.max_expansions);
  EXPECT_EQ(got.fusion.variance_per_m2, want.fusion.variance_per_m2);
  EXPECT_EQ(got.odometry.gicp.max_correspondence_m, 0.1);  // default_odometry()
  EXPECT_EQ(got.odometry.min_points, want.odometry.min_points);

  // The layout's top level: the navigator's scalars, then its three components.
  std::vector<std::string> top;
  for (const auto& line : lines_of(text))
    if (!line.empty() && line[0] != ' ') top.push_back(line.substr(0, line.find(':')));
  const std::vector<std::string> expected{"gicp_correction",
                                          "gicp_voxel_m",
                                          "replan_deviation_m",
                                          "replan_deviation_rad",
                                          "obstacle_margin_m",
                                          "obstacle_step_m",
                                          "max_plans",
                                          "max_recovery_steps",
                                          "planner",
                                          "fusion",
                                          "odometry"};
  EXPECT_EQ(top, expected);
}

// tests/data/navigator_params/footstep_override.yaml names five fields: exactly those five lines of
// the dump change.
TEST(FootstepNavigatorParamsYaml, AFileChangesExactlyTheFieldsItNames) {
  BIPEDNAV_REQUIRE_DATA(file, "navigator_params/footstep_override.yaml");
  const FootstepNavigatorParams before;
  FootstepNavigatorParams p = before;
  navigation::apply_navigator_params_file(file, p);
  EXPECT_EQ(p.replan_deviation_m, 0.05);
  EXPECT_EQ(p.planner.heuristic, "euclidean");
  EXPECT_EQ(p.planner.search.initial_epsilon, 4.0);
  EXPECT_EQ(p.fusion.gate_sigma, 2.5);
  EXPECT_EQ(p.odometry.gicp.max_correspondence_m, 0.2);

  const std::set<std::string> changed =
      changed_lines(navigation::navigator_params_yaml(before), navigation::navigator_params_yaml(p));
  const std::set<std::string> expected{"replan_deviation_m: 0.05", "  heuristic: euclidean", "    initial_epsilon: 4.0",
                                       "  gate_sigma: 2.5", "    max_correspondence_m: 0.2"};
  EXPECT_EQ(changed, expected);
}

TEST(FootstepNavigatorParamsYaml, AnUnknownKeyNamesTheFileAndTheFieldPath) {
  const std::string msg = footstep_error_of("odometry:\n  gicp:\n    max_correspondance_m: 0.2\n");
  EXPECT_NE(msg.find("nao_params.yaml"), std::string::npos) << msg;
  EXPECT_NE(msg.find("odometry.gicp.max_correspondance_m"), std::string::npos) << msg;
  EXPECT_NE(msg.find("unknown parameter"), std::string::npos) << msg;
  // The wheeled navigator's layout is not the footstep navigator's.
  const std::string wheeled = footstep_error_of("control_rate_hz: 10.0\n");
  EXPECT_NE(wheeled.find("nao_params.yaml:control_rate_hz: unknown parameter"), std::string::npos) << wheeled;
  // A field left out of the layout is an unknown key too.
  EXPECT_NE(footstep_error_of("planner: {search: {clock: wall}}").find("planner.search.clock"), std::string::npos);
  EXPECT_NE(footstep_error_of("gicp_correction: 3").find("gicp_correction: expected a value of type bool"),
            std::string::npos);
  EXPECT_NE(
      footstep_error_of("planner: {theta_bins: 2.5}").find("planner.theta_bins: expected a value of type integer"),
      std::string::npos);
}

// Values of the right type but out of range: validate() after the overlay names the field, the error
// the file.
TEST(FootstepNavigatorParamsYaml, ValuesOutOfRangeAreRejectedByValidate) {
  const std::string msg = footstep_error_of("planner: {search: {target_epsilon: 5.0}}");  // > initial_epsilon 3
  EXPECT_NE(msg.find("nao_params.yaml: invalid parameter 'target_epsilon'"), std::string::npos) << msg;
  EXPECT_NE(footstep_error_of("planner: {robot: atlas}").find("invalid parameter 'robot'"), std::string::npos);
  EXPECT_NE(
      footstep_error_of("fusion: {variance_growth_factor: 1.0}").find("invalid parameter 'variance_growth_factor'"),
      std::string::npos);
  EXPECT_NE(footstep_error_of("odometry: {gicp: {covariance_neighbours: 2}}")
                .find("invalid parameter 'covariance_neighbours'"),
            std::string::npos);
  EXPECT_NE(footstep_error_of("max_plans: 0").find("invalid parameter 'max_plans'"), std::string::npos);
  EXPECT_NE(footstep_error_of("replan_deviation_m: .nan").find("invalid parameter 'replan_deviation_m'"),
            std::string::npos);
  EXPECT_EQ(footstep_error_of("gicp_voxel_m: 1\n"), "");  // an integer is a number
}
