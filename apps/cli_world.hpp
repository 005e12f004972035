#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "bipednav/sim/scenario.hpp"

namespace bipednav::app {

// A scenario around any Gazebo world file (`run --world`, `route --world`; sim::scenario_from_world)
// with the start and goal poses given as "x,y[,yaw]" (--start, --goal).
sim::Scenario scenario_from_world(const std::string& world_file, const std::string& robot, const std::string& start,
                                  const std::string& goal);
// --world FILE, --start x,y[,yaw] and --goal x,y[,yaw] on `command`: --world needs both poses and
// excludes the positional `scenario`; the poses need --world.
void add_world_options(CLI::App* command, CLI::Option* scenario, std::string& world, std::string& start,
                       std::string& goal);

}  // namespace bipednav::app
