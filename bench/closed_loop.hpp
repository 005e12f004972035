#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

// The closed loop over scenarios (`bipednav bench scenarios`: every scenario with N seeds, a success
// table) and on one core (`bipednav bench loop`: the whole closed loop's real-time factor).
namespace bipednav::bench {

struct ScenarioBenchOptions {
  int seeds = 1;
  int first_seed = 1;  // seeds first_seed .. first_seed + seeds - 1 (fresh-seed screens)
  int jobs = 1;
  std::vector<std::string> robots{"turtlebot3", "digit"};
  std::vector<std::string> scenarios{"hexagon_static",   "hexagon_dynamic",   "three_rooms",
                                     "digit_lab_static", "digit_lab_dynamic", "turtlebot3_world"};
  std::string params;  // navigation parameters file (RunOptions::params_file)
};

// Runs every scenario with every robot and each seed, `jobs` runs at a time, each on one thread (the
// results do not depend on `jobs`). One row per scenario and robot: the runs that ended as expected
// (SUCCESS, or NO_PATH_FOUND/BLOCKED_GOAL when the widest route to the last goal keeps less room than
// the global planner's clearance allowance), the successes, mean real-time factor and simulated time,
// the route's margins and the failed seeds. Returns {rows, as_expected, succeeded, runs, first_seed,
// jobs}; throws Error for bad options.
nlohmann::json run_scenario_bench(const ScenarioBenchOptions& options);

struct LoopBenchOptions {
  std::string scenario = "hexagon_static";
  std::string robot;  // empty: the scenario's
  int runs = 3;
  std::string params;  // navigation parameters file (RunOptions::params_file)
};

// The whole closed loop (simulator included) on one thread, `runs` times one after another; the
// real-time factor is simulated time over process CPU time, medians over the runs against the 10x
// goal (`meets_goal`).
nlohmann::json run_loop_bench(const LoopBenchOptions& options);

}  // namespace bipednav::bench
