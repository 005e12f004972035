#pragma once

#include <filesystem>
#include <string>

namespace bipednav::app {

// The source tree's scenarios/ directory (scenario files and their worlds).
std::filesystem::path scenario_dir();
// "hexagon_static" (scenarios/NAME.yaml) or a path to a scenario file; throws Error when it is neither.
std::filesystem::path resolve_scenario(const std::string& name);

}  // namespace bipednav::app
