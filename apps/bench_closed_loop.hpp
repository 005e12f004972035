#pragma once

#include <CLI/CLI.hpp>

namespace bipednav::app {

// `bipednav bench scenarios` and `bipednav bench loop --json`: the closed loop's success table over
// seeds and its real-time factor on one core. Called by add_run_commands() (apps/cmd_run.cpp).
void add_closed_loop_benches(CLI::App& bench);

}  // namespace bipednav::app
