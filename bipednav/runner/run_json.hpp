#pragma once

#include <nlohmann/json.hpp>

#include "bipednav/runner/scenario_runner.hpp"

namespace bipednav::runner {

// A closed-loop run as `run.json` holds it, the same for wheeled and footstep runs: scenario, robot,
// seed, success and verdict, the navigator's outcome and message, contacts, the time of first
// arrival, the final true and estimated poses, errors, recoveries, CPU time and fault counters.
nlohmann::json run_result_json(const RunResult& r);

}  // namespace bipednav::runner
