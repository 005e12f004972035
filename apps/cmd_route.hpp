#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "bipednav/common/robot_profile.hpp"
#include "bipednav/sim/scenario.hpp"

namespace bipednav::app {

// `bipednav route SCENARIO`: the widest route of the scenario's static world from its start to
// each goal, against the room the robot needs. Called by add_sim_commands() (apps/cmd_sim.cpp).
void add_route_command(CLI::App& app);

// The report of `route --json` (also each row of `bench scenarios`): the robot's needed clearance,
// each goal's widest route and margin, and the smallest margin.
nlohmann::json route_report(const sim::Scenario& scenario, const RobotProfile& robot, double resolution_m);

}  // namespace bipednav::app
