#pragma once

#include <filesystem>

#include "bipednav/runner/scenario_runner.hpp"

namespace bipednav::runner {

// A figure like the thesis' Fig. 6.1: the world (grey, for reference), global-map obstacles
// (black), local-map obstacles (purple) and inflation (blue), the global path (red), the local
// trajectory (green), the travelled path (purple), the goals (red, then blue circles) and the
// robot (red arrow) at the end of the run, followed by one panel per replanning snapshot.
void write_run_figure(const std::filesystem::path& file, const sim::Scenario& scenario, const RunResult& run);

}  // namespace bipednav::runner
