// The footstep navigator's parameters file (a humanoid's `bipednav params` / `run --params`): dump,
// read back, overrides and errors.
#include <gtest/gtest.h>

#include <set>
#include <sstream>
#include <vector>

#include "bipednav/navigation/navigator_params_yaml.hpp"
#include "test_data.hpp"

using namespace bipednav;
using navigation::FootstepNavigatorParams;

namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// read_navigator_params on YAML text onto the defaults; the error message ("" when it did not throw).
std::string footstep_error_of(const std::string& yaml) {
  FootstepNavigatorParams p;
  try {
    io::ParamReader r = io::ParamReader::from_string(yaml, "nao_params.yaml");
    navigation::read_navigator_params(r, p);
  } catch (const FileError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

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
  got.planner.stance_level_heuristic = true;
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
  EXPECT_FALSE(got.planner.stance_level_heuristic);
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

  const auto a = lines_of(navigation::navigator_params_yaml(before)),
             b = lines_of(navigation::navigator_params_yaml(p));
  ASSERT_EQ(a.size(), b.size());
  std::set<std::string> changed;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i] != b[i]) changed.insert(b[i]);
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
