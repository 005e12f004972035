#pragma once

#include <filesystem>
#include <string>

#include "bipednav/common/robot_profile.hpp"
#include "bipednav/navigation/footstep_navigator.hpp"
#include "bipednav/navigation/navigator.hpp"

namespace bipednav::navigation {

// Loads a robot profile: a name is config/<name>.yaml (config_dir, default config_dir()); an
// argument ending in .yaml or .yml, or containing a '/', is a profile file of the user's own robot
// (config/README.md gives the format). An unknown name is an Error listing the profiles there.
RobotProfile load_robot(const std::string& name_or_file, const std::filesystem::path& config_dir = {});

// The robot's navigation tuning: config/<name>.params.yaml beside the profiles (config_dir, default
// config_dir()), <name> the profile's name, in the layout of the navigator its kind runs
// (navigator_params_yaml.hpp). Empty when there is none: a profile of your own gets the structs'
// defaults and the values derived from the profile.
std::filesystem::path robot_params_file(const RobotProfile& robot, const std::filesystem::path& config_dir = {});

// The navigator's parameters for `robot`, in layers: the structs' defaults with the values derived
// from the profile (NavigatorParams::for_robot), the robot's tuning (robot_params_file), then the
// navigation parameters file `params_file` (empty: none; navigator_params_yaml.hpp reads it). Callers
// put their single overrides (command-line options, ROS parameters) on top. `config_dir` as in
// load_robot (empty: config_dir()).
NavigatorParams navigator_params_for(const RobotProfile& robot, const std::filesystem::path& params_file = {},
                                     const std::filesystem::path& config_dir = {});
// The same layers for the footstep navigator of a humanoid (kind humanoid): its defaults, the robot's
// tuning, then `params_file`, both in the footstep layout.
FootstepNavigatorParams footstep_navigator_params_for(const RobotProfile& robot,
                                                      const std::filesystem::path& params_file = {},
                                                      const std::filesystem::path& config_dir = {});

}  // namespace bipednav::navigation
