#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "bipednav/common/pose2.hpp"
#include "bipednav/sim/scenario.hpp"

namespace bipednav::sim {

// The source tree's scenarios/ directory (scenario files and their worlds).
std::filesystem::path scenario_dir();
// "hexagon_static" (scenarios/NAME.yaml) or a path to a scenario file; throws Error when it is neither.
std::filesystem::path resolve_scenario(const std::string& name);
// Where `model://` URIs of a world resolve: GAZEBO_MODEL_PATH (as Gazebo does), the world's
// ../models, and the Gazebo models that come with the scenarios.
std::vector<std::filesystem::path> world_model_paths(const std::filesystem::path& world_file);
// A scenario around any Gazebo world file (`run --world`, `route --world`, a case of `bench worlds
// --cases`): the robot (default turtlebot3), start and goal poses, bounds around world, start and
// goal, a 180 s time limit.
Scenario scenario_from_world(const std::filesystem::path& world_file, const std::string& robot, const Pose2& start,
                             const Pose2& goal);

}  // namespace bipednav::sim
