#pragma once

#include <CLI/CLI.hpp>

namespace bipednav::app {

// `bipednav route SCENARIO`: the widest route of the scenario's static world from its start to
// each goal, against the room the robot needs. Called by add_sim_commands() (apps/cmd_sim.cpp).
void add_route_command(CLI::App& app);

}  // namespace bipednav::app
