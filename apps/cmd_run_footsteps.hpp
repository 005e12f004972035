#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "bipednav/sim/scenario.hpp"

namespace bipednav::app {

// Whether `bipednav run` drives this scenario's robot (or `robot_override`) by footsteps: a
// profile of kind humanoid.
bool runs_by_footsteps(const sim::Scenario& scenario, const std::string& robot_override);

// `bipednav run` for a humanoid: the footstep closed loop (runner/footstep_runner.hpp), writing
// run.json and run.png to `out`. seed 0 / time_limit_s 0 keep the scenario's; `params_file` (empty:
// none) overlays the footstep navigator's defaults (runner::footstep_navigator_params).
void run_footsteps_command(sim::Scenario scenario, const std::string& robot_override, const std::filesystem::path& out,
                           std::uint64_t seed, double time_limit_s, const std::filesystem::path& params_file = {},
                           const std::filesystem::path& replay = {});

}  // namespace bipednav::app
