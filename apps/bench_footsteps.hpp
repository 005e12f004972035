#pragma once

#include <CLI/CLI.hpp>

namespace bipednav::app {

// `bipednav bench footsteps --json`: Table I of the footstep reference on random cluttered
// heightmaps. Called by add_footstep_commands() (apps/cmd_footstep.cpp).
void add_footstep_bench(CLI::App& bench);

}  // namespace bipednav::app
