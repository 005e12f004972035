#pragma once

#include <CLI/CLI.hpp>

namespace bipednav::app {

// `bipednav bench worlds`: generated crowd and clutter worlds (sim/world_generator.hpp), or a
// user's cases file, run with each robot; success, contacts and time-outs with 95 % intervals.
void add_world_benches(CLI::App& bench);

}  // namespace bipednav::app
