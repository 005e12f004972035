#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "bipednav/common/robot_profile.hpp"
#include "bipednav/navigation/footstep_navigator.hpp"
#include "bipednav/sim/scenario.hpp"

namespace bipednav::app {

// Whether `bipednav run` drives this scenario's robot (or `robot_override`) by footsteps: a
// profile of kind humanoid.
bool runs_by_footsteps(const sim::Scenario& scenario, const std::string& robot_override);

// The footstep navigator's parameters for `robot` with `params_file` overlaid
// (runner::footstep_navigator_params); a file in the wheeled navigator's layout is reported as such.
navigation::FootstepNavigatorParams footstep_params_for_cli(const RobotProfile& robot,
                                                            const std::filesystem::path& params_file);

// Overrides of a footstep run from the command line (unset: the scenario's).
struct FootstepRunArgs {
  std::optional<std::uint64_t> seed;
  std::optional<double> time_limit_s;
  bool progress = true;  // the progress bar (on a terminal only)
  bool json = false;     // --json: one JSON object on stdout instead of the text summary
};

// `bipednav run` for a humanoid: the footstep closed loop (runner/footstep_runner.hpp), writing
// run.json and run.png to `out`; `params_file` (empty: none) overlays the footstep navigator's
// defaults (runner::footstep_navigator_params). Returns the run's success (the exit status).
bool run_footsteps_command(sim::Scenario scenario, const std::string& robot_override, const std::filesystem::path& out,
                           const FootstepRunArgs& args, const std::filesystem::path& params_file = {},
                           const std::filesystem::path& replay = {});

}  // namespace bipednav::app
