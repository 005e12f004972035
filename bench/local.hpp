#pragma once

#include <nlohmann/json.hpp>
#include <string>

// `bipednav bench local`: the TEB local planner's cycle time (with homotopy classes) in seeded scenes
// of 0, 20 and 100 obstacles.
namespace bipednav::bench {

struct LocalBenchOptions {
  int cycles = 100;                  // control cycles per obstacle count
  int threads = 1;                   // threads for the homotopy candidates
  std::string params;                // a navigation parameters file: its TEB settings (server.local.teb)
  std::string robot = "turtlebot3";  // the robot whose defaults the file overlays
};

// Without a parameters file: TebParams' own defaults (the figures in the README); with one: the
// robot's TEB settings with the file overlaid, as `run --params` would use them. Returns the timings
// per obstacle count, those with 100 obstacles against the goals (median 10 ms, p99 25 ms); throws
// Error for a humanoid (it walks by footsteps, no TEB).
nlohmann::json run_local_bench(const LocalBenchOptions& options);

}  // namespace bipednav::bench
