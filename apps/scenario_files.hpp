#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>
#include <vector>

#include "bipednav/sim/scenario.hpp"

namespace bipednav::app {

// The source tree's scenarios/ directory (scenario files and their worlds).
std::filesystem::path scenario_dir();
// "hexagon_static" (scenarios/NAME.yaml) or a path to a scenario file; throws Error when it is neither.
std::filesystem::path resolve_scenario(const std::string& name);
// Where `model://` URIs of a world resolve: GAZEBO_MODEL_PATH (as Gazebo does), the world's
// ../models, and the Gazebo models that come with the scenarios.
std::vector<std::filesystem::path> world_model_paths(const std::filesystem::path& world_file);
// A scenario around any Gazebo world file (`run --world`, `route --world`): the robot (default
// turtlebot3), start and goal poses as "x,y[,yaw]" (--start, --goal), bounds around world, start and
// goal, a 180 s time limit.
sim::Scenario scenario_from_world(const std::string& world_file, const std::string& robot, const std::string& start,
                                  const std::string& goal);
// The same from poses (a case of `bench worlds --cases`).
sim::Scenario scenario_from_world(const std::filesystem::path& world_file, const std::string& robot, const Pose2& start,
                                  const Pose2& goal);
// --world FILE, --start x,y[,yaw] and --goal x,y[,yaw] on `command`: --world needs both poses and
// excludes the positional `scenario`; the poses need --world.
void add_world_options(CLI::App* command, CLI::Option* scenario, std::string& world, std::string& start,
                       std::string& goal);

}  // namespace bipednav::app
