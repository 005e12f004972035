#pragma once

#include <nlohmann/json.hpp>
#include <string>

// `bipednav bench local`: the TEB local planner's cycle time (with homotopy classes) in seeded scenes
// of 0, 20 and 100 obstacles.
namespace bipednav::bench {

struct LocalBenchOptions {
  int cycles = 100;    // control cycles per obstacle count
  int threads = 1;     // threads for the homotopy candidates
  std::string params;  // a navigation parameters file: its TEB settings (server.local.teb)
  std::string robot;   // the robot whose TEB settings are measured (with only `params`: turtlebot3)
};

// Without a robot and a parameters file: TebParams' own defaults; with a robot: its TEB settings as
// `run` uses them (the profile's derived values and config/<robot>.params.yaml), with `params`
// overlaid as `run --params` would overlay it. Returns the timings per obstacle count, those with
// 100 obstacles against the goals (median 10 ms, p99 25 ms of the thread's CPU time); throws Error
// for a humanoid (it walks by footsteps, no TEB).
nlohmann::json run_local_bench(const LocalBenchOptions& options);

}  // namespace bipednav::bench
