#pragma once

#include <filesystem>
#include <string>

#include "bipednav/common/robot_profile.hpp"
#include "bipednav/navigation/navigator.hpp"

namespace bipednav::navigation {

// Loads a robot profile: a name is config/<name>.yaml (config_dir, default config_dir()); an
// argument ending in .yaml or .yml, or containing a '/', is a profile file of the user's own robot
// (config/README.md gives the format). An unknown name is an Error listing the profiles there.
RobotProfile load_robot(const std::string& name_or_file, const std::filesystem::path& config_dir = {});

// The navigator's parameters for `robot`, in layers: the structs' defaults with the robot's tuning
// (NavigatorParams::for_robot), then the navigation parameters file `params_file` (empty: none;
// navigator_params_yaml.hpp reads it). Callers put their single overrides (command-line options,
// ROS parameters) on top.
NavigatorParams navigator_params_for(const RobotProfile& robot, const std::filesystem::path& params_file = {});

}  // namespace bipednav::navigation
