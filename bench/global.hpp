#pragma once

#include <nlohmann/json.hpp>
#include <string>

// `bipednav bench global`: D* Lite's replanning against A*'s in the three-room world, and both
// planners' first plans on the Moving AI maps.
namespace bipednav::bench {

struct GlobalBenchOptions {
  std::string movingai_dir;  // with maps/ and scen/ (empty: tests/data/movingai, looked for)
  int max_replans = 2000;    // replan limit
};

// Runs the replanning benchmark (planning::global::run_replan_benchmark) and the Moving AI first plans
// (planning::global::movingai_first_plans; null with a note when the maps are not found). Returns the
// figures with their goals (expansions and CPU time ratios).
nlohmann::json run_global_bench(const GlobalBenchOptions& options);

}  // namespace bipednav::bench
