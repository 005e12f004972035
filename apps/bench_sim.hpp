#pragma once

#include <CLI/CLI.hpp>

namespace bipednav::app {

// `bipednav bench sim --json`: Digit's full sensor suite in a furnished room, one core.
// Called by add_sim_commands() (apps/cmd_sim.cpp).
void add_sim_bench(CLI::App& bench);

}  // namespace bipednav::app
