#pragma once

#include <CLI/CLI.hpp>

// Each module's command-line adapter adds its subcommands to `app` and its benchmarks to
// `bench` (reached as `bipednav bench NAME --json`). One file per module: apps/cmd_<module>.cpp.
namespace bipednav::app {

void add_sim_commands(CLI::App& app, CLI::App& bench);           // sim, bench sim
void add_cloud_commands(CLI::App& app, CLI::App& bench);         // cloud filter/segment, bench perception
void add_mapping_commands(CLI::App& app, CLI::App& bench);       // costmap, bench mapping
void add_plan_commands(CLI::App& app, CLI::App& bench);          // plan grid/movingai, bench global
void add_local_commands(CLI::App& app, CLI::App& bench);         // local, bench local
void add_localization_commands(CLI::App& app, CLI::App& bench);  // register, odometry, bench localization
void add_footstep_commands(CLI::App& app, CLI::App& bench);      // footsteps, bench footsteps
void add_run_commands(CLI::App& app, CLI::App& bench);           // run, params, bench scenarios
void add_tracking_commands(CLI::App& app, CLI::App& bench);      // bench tracking

}  // namespace bipednav::app
